#include "gcode/transform/relayer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gcode/core/line_builder.hpp"
#include "gcode/core/number.hpp"

namespace gcode {

namespace {

double height_of(const LayerIndex& index, int k) {
  const LayerInfo& l = index.layer(k).info;
  if (l.height > 0) return l.height;
  return k > 1 ? l.z - index.layer(k - 1).info.z : l.z;
}

std::string list_layers(const std::vector<int>& layers) {
  std::string s;
  for (int l : layers) s += (s.empty() ? "" : ", ") + std::to_string(l);
  return s;
}

}  // namespace

Join choose_join(LayerIndex& next, double printed_z, int z_decimals, double tolerance) {
  const int zd = std::max(z_decimals, 3);
  next.reach_above(printed_z, 2);
  int k = 0;
  for (int i = 1; i <= next.layers() && k == 0; ++i)
    if (next.layer(i).info.z > printed_z + 1e-6) k = i;
  if (k == 0)
    throw std::runtime_error(next.layers() == 0 ? fmt::format("{} has no layers", next.name())
                                                : fmt::format("{} has no layer above Z {} (its last is at Z {})",
                                                              next.name(), number_string(printed_z, 4),
                                                              number_string(next.layer(next.layers()).info.z, 4)));
  Join join;
  const Fixed printed = Fixed::from_double(printed_z).rounded(zd);
  for (;;) {
    const double z = next.layer(k).info.z;
    const double h = height_of(next, k);
    const double r = z - printed_z;
    if (r < h - tolerance) {
      // Its bottom lies below what is printed: already covered.
      if (!next.reach(k + 1)) {
        // The last layer: print it thinner rather than not at all.
        join.first = k;
        join.first_scale = h > 0 ? r / h : 1;
        return join;
      }
      join.covered.push_back(k++);
      continue;
    }
    join.first = k;
    if (r <= h + tolerance) return join;
    // A gap under it: the missing height in layers no thicker than its own,
    // printed with its paths.
    const double gap = r - h;
    const int n = std::max(1, static_cast<int>(std::ceil((gap - tolerance) / h)));
    Fixed below = printed;
    const Fixed layer_z = Fixed::from_double(z).rounded(zd);
    for (int i = 1; i <= n; ++i) {
      Fixed at = (printed + Fixed::from_double(gap * i / n)).rounded(zd);
      JoinStep step;
      step.layer = k;
      step.z_shift = at - layer_z;
      step.scale = (at - below).to_double() / h;
      join.fills.push_back(step);
      below = at;
    }
    return join;
  }
}

Candidates layer_candidates(LayerIndex& index, double z, double tolerance) {
  index.reach_above(z + tolerance, 0);
  Candidates c;
  for (int i = 1; i <= index.layers(); ++i) {
    if (index.layer(i).info.z <= z + tolerance) {
      c.below = i;
    } else {
      c.above = i;
      break;
    }
  }
  return c;
}

// ---------------------------------------------------------------------------

RelayerPlan::RelayerPlan(LayerIndex& next, Options options, Diagnostics* diag)
    : next_(next), options_(std::move(options)), diag_(diag) {}

LayerAction RelayerPlan::at_layer(const LayerInfo& info, const SpliceContext& context) {
  ++layers_seen_;
  bool keep = options_.at_z ? info.z <= *options_.at_z + 1e-6 : info.index <= options_.at_layer;
  if (keep) {
    last_ = info;
    LayerAction a;
    a.shift = context.shift;
    return a;
  }
  if (last_.index == 0)
    throw std::runtime_error(options_.at_z ? fmt::format("--at-z {}: the input's first layer is higher (Z {})",
                                                         number_string(*options_.at_z, 4), number_string(info.z, 4))
                                           : std::string("--at-layer: the input has no such layer"));
  return join(context);
}

LayerAction RelayerPlan::at_end_code(const SpliceContext& context) {
  if (layers_seen_ == 0) throw std::runtime_error("the input has no layers");
  if (!options_.at_z && options_.at_layer > layers_seen_)
    throw std::runtime_error(
        fmt::format("--at-layer {}: the input has {} layers", options_.at_layer, layers_seen_));
  // Every layer of the input is at or below the height: the new file goes on from its top.
  return join(context);
}

namespace {

// A join that has to squeeze or stretch a layer by half or more shows on the
// part: the user should know before the printer does it.
void warn_if_uneven(const LayerIndex& next, const Join& j, Diagnostics* diag) {
  if (diag == nullptr) return;
  auto uneven = [](double scale) { return scale < 0.5 || scale > 1.5; };
  if (uneven(j.first_scale))
    diag->warn(fmt::format("{} layer {} is printed with its extrusion x{} at the join: the seam may show", next.name(),
                           j.first, number_string(j.first_scale, 4)));
  for (const JoinStep& s : j.fills)
    if (uneven(s.scale))
      diag->warn(fmt::format("{} layer {} fills the gap with its extrusion x{}: the seam may show", next.name(),
                             s.layer, number_string(s.scale, 4)));
}

}  // namespace

JoinBlocks join_blocks(LayerIndex& next, double printed_z, int z_decimals, const Box2& printed_extent,
                       const std::string& onto, const std::string& note_prefix, Diagnostics* diag) {
  JoinBlocks out;
  Join& j = out.join;
  j = choose_join(next, printed_z, z_decimals);
  const int first_new = !j.covered.empty() ? j.covered.front() : j.first;
  // The new file's part below the join must lie where the old one printed.
  std::string error = placement_difference(printed_extent, next.extent(1, first_new - 1), next.name());
  if (!error.empty()) throw std::runtime_error(error);
  if (!j.covered.empty())
    out.report.push_back(fmt::format("{} layer{} {} left out: already covered", next.name(),
                                     j.covered.size() > 1 ? "s" : "", list_layers(j.covered)));
  for (const JoinStep& s : j.fills) {
    SpliceBlock b = layer_index_block(next, s.layer, s.layer);
    b.z_shift = s.z_shift;
    b.extrusion_scale = s.scale;
    const double at = next.layer(s.layer).info.z + s.z_shift.to_double();
    b.note = fmt::format("{}layer {} of {} at Z {}, extrusion x{}: the height missing under its layer {}", note_prefix,
                         s.layer, next.name(), number_string(at, 4), number_string(s.scale, 4), s.layer);
    out.report.push_back(fmt::format("{} layer {} printed first at Z {} with its extrusion x{} (the missing {} mm)",
                                     next.name(), s.layer, number_string(at, 4), number_string(s.scale, 4),
                                     number_string(s.scale * height_of(next, s.layer), 4)));
    out.blocks.push_back(std::move(b));
  }
  SpliceBlock rest = layer_index_block(next, j.first, j.first, true);
  rest.extrusion_scale = j.first_scale;
  const LayerInfo& f = next.layer(j.first).info;
  rest.note = fmt::format("{}{} from its layer {} (Z {}) on, joined onto {}", note_prefix, next.name(), j.first,
                          number_string(f.z, 4), onto);
  out.report.push_back(
      fmt::format("{} goes on from its layer {} (Z {}) to its end", next.name(), j.first, number_string(f.z, 4)));
  if (j.first_scale != 1)
    out.report.push_back(fmt::format("{} layer {} overlaps the print: its extrusion x{}", next.name(), j.first,
                                     number_string(j.first_scale, 4)));
  warn_if_uneven(next, j, diag);
  out.blocks.push_back(std::move(rest));
  return out;
}

LayerAction RelayerPlan::join(const SpliceContext& context) {
  joined_ = true;
  const double printed = last_.z + context.shift.to_double();
  JoinBlocks j = join_blocks(next_, printed, options_.z_decimals, context.extent,
                             fmt::format("the input's layer {} (Z {})", last_.index, number_string(last_.z, 4)),
                             options_.note_prefix, diag_);
  report_.push_back(fmt::format("the input's layers 1-{} (to Z {}) are kept", last_.index, number_string(last_.z, 4)));
  report_.insert(report_.end(), j.report.begin(), j.report.end());
  LayerAction a;
  a.leave = true;
  a.shift = context.shift;
  a.blocks = std::move(j.blocks);
  return a;
}

// ---------------------------------------------------------------------------

ResumePlan::ResumePlan(Options options, Diagnostics* diag) : options_(std::move(options)), diag_(diag) {}

LayerAction ResumePlan::at_layer(const LayerInfo& info, const SpliceContext& context) {
  LayerAction a;
  a.shift = context.shift;
  if (resumed_) return a;
  if (info.z <= options_.z + kJoinTolerance) {
    last_skipped_ = info;
    a.keep = false;
    return a;
  }
  resumed_ = true;
  first_ = info;
  a.lead_in = lead_in(info, *context.main);
  a.printed_top = options_.z;
  a.note = fmt::format("{}layer {} (Z {}) on", options_.note_prefix, info.index, number_string(info.z, 4));
  report_.push_back(fmt::format("resuming at layer {} (Z {}) on a part measured at Z {}", info.index,
                                number_string(info.z, 4), number_string(options_.z, 4)));
  if (info.z - options_.z > 2 * (info.height > 0 ? info.height : 0.2) + kJoinTolerance && diag_ != nullptr)
    diag_->warn(fmt::format("layer {} (Z {}) is {} mm above the measured Z {}: check the height", info.index,
                            number_string(info.z, 4), number_string(info.z - options_.z, 4),
                            number_string(options_.z, 4)));
  return a;
}

LayerAction ResumePlan::at_end_code(const SpliceContext& context) {
  if (!resumed_)
    throw std::runtime_error(last_skipped_.index == 0
                                 ? std::string("the file has no layers")
                                 : fmt::format("nothing to resume: the file's last layer is at Z {}, at or below {}",
                                               number_string(last_skipped_.z, 4), number_string(options_.z, 4)));
  LayerAction a;
  a.shift = context.shift;
  return a;
}

std::vector<std::string> ResumePlan::lead_in(const LayerInfo& info, const StreamPoint& main) const {
  const Options& o = options_;
  const int zd = std::max(o.z_decimals, 3), ed = std::max(o.e_decimals, 1);
  std::vector<std::string> lines;
  LineBuilder b;
  lines.push_back(fmt::format("; {}resume at layer {} (Z {}) of a part measured at Z {}", o.note_prefix, info.index,
                              number_string(info.z, 4), number_string(o.z, 4)));
  // Heat first, the bed before the nozzle, and wait: the part stays stuck
  // and nothing moves cold.
  using Kind = CarriedSettings::Kind;
  bool hotend = false;
  if (const auto* bed = main.settings.find(Kind::Bed, 0)) {
    b.start("M190").fixed('S', bed->value);
    lines.emplace_back(b.view());
  }
  for (const auto& s : main.settings.all()) {
    if (s.kind != Kind::Hotend) continue;
    hotend = true;
    if (s.text.rfind("G10", 0) == 0) {
      lines.push_back(s.text);
      lines.emplace_back("M116");  // RepRapFirmware: wait for the temperatures
      continue;
    }
    b.start("M109");
    if (s.index != main.state.tool) b.word('T', s.index, 0);
    b.fixed('S', s.value);
    lines.emplace_back(b.view());
  }
  if (!hotend)
    throw std::runtime_error(
        fmt::format("the file sets no nozzle temperature before layer {}: there is nothing to heat to", info.index));
  // Off the part, then declare where the nozzle is: it stopped at the
  // measured height and the lift was relative.
  const Fixed lift = Fixed::from_double(o.lift).rounded(zd);
  lines.emplace_back("G91");
  b.start("G1").fixed('Z', lift).word('F', o.z_speed * 60, 0);
  lines.emplace_back(b.view());
  lines.emplace_back("G90");
  b.start("G92").fixed('Z', (Fixed::from_double(o.z).rounded(zd) + lift));
  lines.emplace_back(b.view());
  lines.emplace_back("G28 X Y");
  if (main.e_mode_set) lines.emplace_back(main.state.relative_e ? "M83" : "M82");
  if (o.purge > 0) {
    double x = o.purge_x, y = o.purge_y;
    if (!o.purge_at_given) {
      if (!o.area.has_bed)
        throw std::runtime_error("the file does not say how big the bed is: give --purge-at X,Y for the purge");
      x = o.area.bed.min_x + 5;
      y = o.area.bed.min_y + 5;
    }
    if (o.area.has_print_box && o.area.print_box.contains(x, y))
      throw std::runtime_error(
          fmt::format("the purge position X{} Y{} is above the part: give --purge-at X,Y away "
                      "from it",
                      number_string(x, 4), number_string(y, 4)));
    b.start("G1").word('X', x, 3).word('Y', y, 3).word('F', o.travel_speed * 60, 0);
    lines.emplace_back(b.view());
    const Fixed amount = Fixed::from_double(o.purge).rounded(ed);
    if (main.e_mode_set && main.state.relative_e) {
      b.start("G1").fixed('E', amount).word('F', o.purge_speed * 60, 0);
    } else {
      lines.emplace_back("G92 E0");
      b.start("G1").fixed('E', amount).word('F', o.purge_speed * 60, 0);
    }
    lines.emplace_back(b.view());
  }
  return lines;
}

}  // namespace gcode
