#include "gcode/transform/layer_edits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "gcode/core/number.hpp"

namespace gcode {

namespace {

// Heights of layers that are "the same Z" in two slicings of one model.
constexpr double kSameZ = 0.005;

bool all_digits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::string describe(const LayerInfo& l) { return fmt::format("layer {} (Z {})", l.index, number_string(l.z, 4)); }

}  // namespace

LayerPick LayerPick::parse(std::string_view text) {
  LayerPick p;
  p.text_ = std::string(text);
  if (!text.empty() && text.front() == '@') {
    std::string_view z = text.substr(1);
    if (z.find(':') != std::string_view::npos) {
      p.z_ = ZRange::parse(z);
    } else {
      double v = 0;
      if (!parse_number(z, v)) throw std::invalid_argument("bad height '" + p.text_ + "': expected @Z or @Z1:Z2");
      p.z_.low = p.z_.high = v;
    }
    return p;
  }
  p.range_ = LayerRange::parse(text);
  return p;
}

bool LayerPick::contains(const LayerInfo& layer, int total) const {
  return range_ ? range_->contains(layer.index, total) : z_.contains(layer.z);
}

RepeatText RepeatText::parse(std::string_view text) {
  RepeatText r;
  std::string_view layer = text;
  std::size_t x = text.find_last_of("xX");
  if (x != std::string_view::npos) {
    std::string_view n = text.substr(x + 1);
    auto [p, ec] = std::from_chars(n.data(), n.data() + n.size(), r.times);
    if (n.empty() || ec != std::errc() || p != n.data() + n.size() || r.times < 1)
      throw std::invalid_argument("bad --repeat '" + std::string(text) + "': expected LAYER or LAYERxN with N >= 1");
    layer = text.substr(0, x);
  }
  bool single = all_digits(layer) || (layer.size() > 1 && layer.front() == '@' && layer.find(':') == std::string_view::npos);
  if (!single)
    throw std::invalid_argument("bad --repeat '" + std::string(text) + "': one layer (12, or @Z), then xN");
  r.layer = LayerPick::parse(layer);
  return r;
}

FileLayersText FileLayersText::parse(std::string_view text) {
  FileLayersText f;
  std::size_t colon = text.rfind(':');
  if (colon != std::string_view::npos && colon > 0 && colon + 1 < text.size()) {
    try {
      f.layers = LayerPick::parse(text.substr(colon + 1));
      f.file = std::string(text.substr(0, colon));
      return f;
    } catch (const std::invalid_argument&) {
      // Not a range: the colon is part of the file name.
    }
  }
  f.file = std::string(text);
  return f;
}

bool LayerEditsText::needs_total() const {
  auto needs = [](const std::string& t) { return !t.empty() && LayerPick::parse(t).needs_total(); };
  if (needs(skip)) return true;
  for (const auto& t : replace)
    if (needs(t)) return true;
  return false;  // --repeat and --insert-after name one layer; FILE:LAYERS is counted in FILE
}

std::vector<std::string> LayerEditsText::files() const {
  std::vector<std::string> names;
  for (const auto& t : with) names.push_back(FileLayersText::parse(t).file);
  for (const auto& f : insert_file) names.push_back(f);
  return names;
}

void LayerEditsText::validate() const {
  if (!any()) throw std::invalid_argument("nothing to do: give --layer/--with, --skip, --repeat or --insert-after/--file");
  if (replace.size() != with.size())
    throw std::invalid_argument(fmt::format("--layer and --with come in pairs ({} --layer, {} --with)", replace.size(),
                                            with.size()));
  if (insert_after.size() != insert_file.size())
    throw std::invalid_argument(fmt::format("--insert-after and --file come in pairs ({} --insert-after, {} --file)",
                                            insert_after.size(), insert_file.size()));
  if (keep_z && skip.empty()) throw std::invalid_argument("--keep-z goes with --skip");
  std::optional<LayerPick> skipped;
  if (!skip.empty()) skipped = LayerPick::parse(skip);
  std::vector<LayerPick> replaced, repeated, inserted;
  for (const auto& t : replace) replaced.push_back(LayerPick::parse(t));
  for (const auto& t : with) FileLayersText::parse(t);
  for (const auto& t : repeat) repeated.push_back(RepeatText::parse(t).layer);
  for (const auto& t : insert_after) {
    LayerPick p = LayerPick::parse(t);
    bool single = all_digits(t) || (t.size() > 1 && t.front() == '@' && t.find(':') == std::string::npos);
    if (!single) throw std::invalid_argument("bad --insert-after '" + t + "': one layer (12, or @Z)");
    inserted.push_back(p);
  }
  // Layer numbers named twice over: checked here for numbers (heights and
  // ranges from the end are known only with the input).
  int highest = skipped ? skipped->highest_named() : 0;
  for (const auto* list : {&replaced, &repeated, &inserted})
    for (const LayerPick& p : *list) highest = std::max(highest, p.highest_named());
  for (int l = 1; l <= highest + 1; ++l) {
    LayerInfo info;
    info.index = l;
    info.z = -1e300;  // no height matches
    auto in = [&](const LayerPick& p) { return !p.by_height() && !p.needs_total() && p.contains(info, 0); };
    bool skip_here = skipped && in(*skipped);
    int replaced_here = 0;
    for (const LayerPick& p : replaced) replaced_here += in(p) ? 1 : 0;
    bool repeat_here = std::any_of(repeated.begin(), repeated.end(), in);
    bool insert_here = std::any_of(inserted.begin(), inserted.end(), in);
    if (skip_here && replaced_here > 0)
      throw std::invalid_argument(fmt::format("layer {} is both left out (--skip) and replaced (--layer)", l));
    if (replaced_here > 1) throw std::invalid_argument(fmt::format("layer {} is replaced twice (--layer)", l));
    if ((skip_here || replaced_here > 0) && (repeat_here || insert_here))
      throw std::invalid_argument(fmt::format("layer {} is {} and has --{} on it: {} the layer before it instead", l,
                                              skip_here ? "left out" : "replaced",
                                              repeat_here ? "repeat" : "insert-after",
                                              repeat_here ? "repeat" : "insert after"));
  }
}

LayerEditPlan::LayerEditPlan(const LayerEditsText& text, int main_fd, const LayerMarkers& markers,
                             std::vector<SpliceFile> files, int total, int z_decimals, Diagnostics* diag,
                             std::string note_prefix)
    : main_fd_(main_fd),
      markers_(markers),
      keep_z_(text.keep_z),
      total_(total),
      z_decimals_(z_decimals),
      diag_(diag),
      note_(std::move(note_prefix)) {
  auto file = [&](const std::string& name) {
    for (const SpliceFile& f : files)
      if (f.name == name) return f;
    throw std::logic_error("LayerEditPlan: no open file " + name);
  };
  if (!text.skip.empty()) skip_ = LayerPick::parse(text.skip);
  for (std::size_t i = 0; i < text.replace.size(); ++i) {
    FileLayersText w = FileLayersText::parse(text.with[i]);
    Replace r{LayerPick::parse(text.replace[i]), file(w.file), {}, 0, false};
    if (w.layers) {
      LayerIndex& index = *r.file.index;
      index.read_all();
      for (int j = 1; j <= index.layers(); ++j)
        if (w.layers->contains(index.layer(j).info, index.layers())) r.file_layers.push_back(j);
      if (r.file_layers.empty())
        throw std::runtime_error(fmt::format("{} has no layer {} (it has {})", w.file, w.layers->text(), index.layers()));
    }
    replace_.push_back(std::move(r));
  }
  for (const auto& t : text.repeat) {
    RepeatText r = RepeatText::parse(t);
    repeat_.push_back(Repeat{r.layer, r.times, false});
  }
  for (std::size_t i = 0; i < text.insert_after.size(); ++i)
    insert_.push_back(Insert{LayerPick::parse(text.insert_after[i]), file(text.insert_file[i]), false});
  if (!repeat_.empty() && main_fd_ < 0) throw std::logic_error("LayerEditPlan: --repeat needs the input's descriptor");
}

Fixed LayerEditPlan::z_of(double z) const { return Fixed::from_double(z).rounded(std::max(z_decimals_, 4)); }

void LayerEditPlan::check_placement(const SpliceFile& file, int below, const SpliceContext& context) {
  if (std::find(checked_.begin(), checked_.end(), file.name) != checked_.end()) return;
  checked_.push_back(file.name);
  std::string error = placement_difference(context.extent, file.index->extent(1, below), file.name);
  if (!error.empty()) throw std::runtime_error(error);
}

void LayerEditPlan::after_layer(const SpliceContext& context, LayerAction& action) {
  if (context.previous == nullptr) return;
  const PassedLayer& p = *context.previous;
  const Fixed h = z_of(p.info.height);
  for (Repeat& r : repeat_) {
    if (!r.layer.contains(p.info, total_)) continue;
    r.matched = true;
    for (int k = 1; k <= r.times; ++k) {
      SpliceBlock b;
      b.fd = main_fd_;
      b.name = "the input";
      b.markers = &markers_;
      b.begin = p.info.offset;
      b.end = p.end;
      b.first_line = p.info.first_line;
      b.first_layer = p.info;
      b.start = p.start;
      b.z_shift = action.shift + h;
      action.shift = b.z_shift;
      b.note = fmt::format("{}{} again ({} of {}) at Z {}", note_, describe(p.info), k, r.times,
                           number_string((z_of(p.info.z) + b.z_shift).to_double(), 4));
      action.blocks.push_back(std::move(b));
    }
    report_.push_back(fmt::format("{} printed {} more time{}; later layers {} mm up", describe(p.info), r.times,
                                  r.times > 1 ? "s" : "", number_string((h.to_double() * r.times), 4)));
  }
  for (Insert& in : insert_) {
    if (!in.after.contains(p.info, total_)) continue;
    in.matched = true;
    LayerIndex& index = *in.file.index;
    index.read_all();
    if (index.layers() == 0) throw std::runtime_error(fmt::format("{} has no layers to insert", in.file.name));
    const IndexedLayer& first = index.layer(1);
    const Fixed bottom = z_of(first.info.z - first.info.height);
    const Fixed height = z_of(index.layer(index.layers()).info.z) - bottom;
    SpliceBlock b = layer_index_block(index, 1, index.layers());
    b.z_shift = z_of(p.info.z) + action.shift - bottom;
    b.note = fmt::format("{}{} ({} layers) on top of {} at Z {}", note_, in.file.name, index.layers(), describe(p.info),
                         number_string((z_of(p.info.z) + action.shift).to_double(), 4));
    action.shift += height;
    action.blocks.push_back(std::move(b));
    report_.push_back(fmt::format("{} ({} layers, {} mm) inserted after {}; later layers {} mm up", in.file.name,
                                  index.layers(), number_string(height.to_double(), 4), describe(p.info),
                                  number_string(height.to_double(), 4)));
  }
}

LayerAction LayerEditPlan::at_layer(const LayerInfo& info, const SpliceContext& context) {
  ++layers_seen_;
  LayerAction action;
  action.shift = context.shift;
  after_layer(context, action);
  if (skip_ && skip_->contains(info, total_)) {
    skip_layer(info, action);
    return action;
  }
  const double scale = fill_scale(info);
  for (Replace& r : replace_) {
    if (!r.layers.contains(info, total_)) continue;
    replace_layer(r, info, context, scale, action);
    return action;
  }
  action.extrusion_scale = scale;
  return action;
}

// --skip: the layer is left out; later layers come down by its height, or
// with --keep-z its height is filled by the next printed layer.
void LayerEditPlan::skip_layer(const LayerInfo& info, LayerAction& action) {
  skip_matched_ = true;
  action.keep = false;
  const Fixed h = z_of(info.height);
  if (keep_z_) {
    if (fill_ == 0) fill_first_ = info.index;
    fill_last_ = info.index;
    fill_ += h.to_double();
  } else {
    action.shift -= h;
  }
  report_.push_back(
      fmt::format("{} left out{}", describe(info),
                  keep_z_ ? "" : fmt::format("; later layers {} mm down", number_string(h.to_double(), 4))));
}

// The extrusion factor of the first layer printed after --keep-z left
// layers out (1 otherwise): it fills their height.
double LayerEditPlan::fill_scale(const LayerInfo& info) {
  if (fill_ <= 0) return 1;
  double h = info.height > 0 ? info.height : 0;
  if (h <= 0) throw std::runtime_error(fmt::format("{} has no height to scale its extrusion by", describe(info)));
  const double scale = (h + fill_) / h;
  std::string what = fill_first_ == fill_last_ ? fmt::format("layer {}", fill_first_)
                                                : fmt::format("layers {}-{}", fill_first_, fill_last_);
  if (diag_ != nullptr)
    diag_->warn(
        fmt::format("--keep-z: {} printed with {} times its extrusion to fill the {} mm of {} left out: "
                    "this over-extrudes by design",
                    describe(info), number_string(scale, 4), number_string(fill_, 4), what));
  report_.push_back(fmt::format("{} extrusion x{} (fills {})", describe(info), number_string(scale, 4), what));
  fill_ = 0;
  return scale;
}

// The layer of a --with file that replaces `info`: the next one it lists,
// else the one at the same Z (an error when it has none).
int LayerEditPlan::replacement_of(Replace& r, const LayerInfo& info) {
  LayerIndex& index = *r.file.index;
  if (!r.file_layers.empty()) {
    if (r.used >= r.file_layers.size())
      throw std::runtime_error(fmt::format("{}: more layers replaced than {} lists ({})", describe(info), r.file.name,
                                           r.file_layers.size()));
    return r.file_layers[r.used++];
  }
  index.reach_above(info.z + kSameZ, 0);
  int j = 0;
  double best = 1e300;
  for (int k = 1; k <= index.layers(); ++k) {
    double d = std::fabs(index.layer(k).info.z - info.z);
    if (d < best) {
      best = d;
      j = k;
    }
  }
  if (j == 0 || best > kSameZ)
    throw std::runtime_error(
        j == 0 ? fmt::format("{} has no layers to replace {} with", r.file.name, describe(info))
               : fmt::format("{} has no layer at Z {} to replace {} with (nearest: layer {} at Z {}); name "
                             "its layers with --with {}:LAYERS",
                             r.file.name, number_string(info.z, 4), describe(info), j,
                             number_string(index.layer(j).info.z, 4), r.file.name));
  return j;
}

// --with: the layer is printed from the other file, at this layer's height.
void LayerEditPlan::replace_layer(Replace& r, const LayerInfo& info, const SpliceContext& context, double scale,
                                  LayerAction& action) {
  r.matched = true;
  LayerIndex& index = *r.file.index;
  const int j = replacement_of(r, info);
  check_placement(r.file, j - 1, context);
  SpliceBlock b = layer_index_block(index, j, j);
  const IndexedLayer& l = index.layer(j);
  b.z_shift = z_of(info.z) + action.shift - z_of(l.info.z);
  if (scale != 1) {
    // The fill goes to the block printed in this layer's place.
    b.extrusion_scale = (l.info.height > 0 ? (l.info.height + (scale - 1) * info.height) / l.info.height : scale);
  }
  b.note = fmt::format("{}{} replaced by layer {} of {} (Z {})", note_, describe(info), j, r.file.name,
                       number_string(l.info.z, 4));
  if (std::fabs(l.info.height - info.height) > 0.01 && diag_ != nullptr)
    diag_->warn(fmt::format("{} is {} mm high, layer {} of {} {} mm: its extrusion is meant for another height",
                            describe(info), number_string(info.height, 4), j, r.file.name,
                            number_string(l.info.height, 4)));
  report_.push_back(
      fmt::format("{} replaced by layer {} of {} (Z {})", describe(info), j, r.file.name, number_string(l.info.z, 4)));
  action.blocks.push_back(std::move(b));
  action.keep = false;
}

LayerAction LayerEditPlan::at_end_code(const SpliceContext& context) {
  LayerAction action;
  action.shift = context.shift;
  after_layer(context, action);
  if (fill_ > 0 && diag_ != nullptr)
    diag_->warn(fmt::format("--keep-z: no layer after layer {} takes the extrusion of the {} mm left out", fill_last_,
                            number_string(fill_, 4)));
  return action;
}

void LayerEditPlan::verify() const {
  auto check = [&](const char* option, const LayerPick& p, bool matched) {
    if (p.by_height()) {
      if (!matched)
        throw std::runtime_error(fmt::format("{} {}: no layer of the input is at that height", option, p.text()));
    } else if (p.highest_named() > layers_seen_ || !matched) {
      throw std::runtime_error(fmt::format("{} {}: the input has {} layers", option, p.text(), layers_seen_));
    }
  };
  if (skip_) check("--skip", *skip_, skip_matched_);
  for (const Replace& r : replace_) {
    check("--layer", r.layers, r.matched);
    if (!r.file_layers.empty() && r.used != r.file_layers.size())
      throw std::runtime_error(fmt::format("--layer {} replaced {} layers but {} lists {}", r.layers.text(), r.used,
                                           r.file.name, r.file_layers.size()));
  }
  for (const Repeat& r : repeat_) check("--repeat", r.layer, r.matched);
  for (const Insert& i : insert_) check("--insert-after", i.after, i.matched);
}

}  // namespace gcode
