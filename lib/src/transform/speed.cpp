#include "gcode/transform/speed.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/feature.hpp"
#include "gcode/core/firmware.hpp"
#include "gcode/core/line_edit.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/core/number.hpp"

namespace gcode {

namespace {

// Decimals of the factor in the marker comment ("x1.6667" on a ramp).
constexpr int kNoteDecimals = 4;

__extension__ using Wide = __int128;

// v x k on exact decimals, rounded half away from zero to 10^-9: F1001 x
// 1.15 is 1151.15 (F1151.2 at one decimal), where doubles give
// 1151.1499999999999 (F1151.1).
Fixed times(Fixed v, Fixed k) {
  Wide p = static_cast<Wide>(v.units()) * k.units();
  Wide q = p / Fixed::kOne, r = p % Fixed::kOne;
  if (2 * (r < 0 ? -r : r) >= Fixed::kOne) q += p < 0 ? -1 : 1;
  if (q > Fixed::kMax) q = Fixed::kMax;
  if (q < -Fixed::kMax) q = -Fixed::kMax;
  return Fixed::from_units(static_cast<std::int64_t>(q));
}

enum class Rounding : std::uint8_t { Nearest, Down, Up };

// `v` with at most `decimals` digits: a value capped from above is rounded
// down, so the written number never exceeds the cap; from below, up.
Fixed round_to(Fixed v, int decimals, Rounding mode) {
  if (mode == Rounding::Nearest) return v.rounded(decimals);
  std::int64_t step = Fixed::kPowersOf10[Fixed::kDecimals - decimals];
  std::int64_t u = v.units(), q = u / step;
  if (u % step != 0) {
    if (mode == Rounding::Down && u < 0) --q;
    if (mode == Rounding::Up && u > 0) ++q;
  }
  return Fixed::from_units(q * step);
}

std::string number(Fixed v, int decimals) {
  char buffer[kMaxNumberChars];
  return std::string(buffer, v.format(decimals, buffer));
}

}  // namespace

M220Restore m220_restore_for_flavor(std::string_view flavor) {
  const FirmwareFlavor* firmware = find_firmware(flavor);
  return firmware != nullptr && firmware->m220_backup_restore ? M220Restore::Backup : M220Restore::Reset;
}

void SpeedOptions::validate() const {
  auto bad = [](double v) { return !std::isfinite(v) || v < 0; };
  if (!std::isfinite(factor) || factor <= 0) throw std::invalid_argument("--factor must be a number above 0");
  if (bad(speed)) throw std::invalid_argument("--speed must be a speed in mm/s above 0");
  if (ramp && (!std::isfinite(ramp_first) || !std::isfinite(ramp_last) || ramp_first <= 0 || ramp_last <= 0))
    throw std::invalid_argument("--ramp: both factors must be numbers above 0");
  if (bad(travel_factor)) throw std::invalid_argument("--travel-factor must be a number above 0");
  if (bad(max_speed)) throw std::invalid_argument("--max-speed must be a speed in mm/s above 0");
  if (bad(min_speed)) throw std::invalid_argument("--min-speed must be a speed in mm/s above 0");
  if (bad(max_flow)) throw std::invalid_argument("--max-flow must be a volume rate in mm3/s above 0");
  if (!std::isfinite(filament_diameter) || filament_diameter <= 0)
    throw std::invalid_argument("--filament-diameter must be a diameter in mm above 0");
  if (max_speed > 0 && min_speed > max_speed)
    throw std::invalid_argument("--min-speed " + number_string(min_speed, 3) + " is above --max-speed " +
                                number_string(max_speed, 3));
  if ((speed > 0) + ramp > 1) throw std::invalid_argument("choose one change: --factor, --speed or --ramp");
  if (m220) {
    if (speed > 0) throw std::invalid_argument("--m220 sets a percentage of the file's speeds; it cannot give --speed");
    if (max_speed > 0 || min_speed > 0 || max_flow > 0)
      throw std::invalid_argument("--m220 scales every move in the firmware; caps (--max-speed, --min-speed, "
                                  "--max-flow) cannot be kept that way");
    if (travel || travel_factor > 0)
      throw std::invalid_argument("--m220 scales travel with everything else; --travel and --travel-factor do not apply");
    for (double f : {ramp ? ramp_first : factor, ramp ? ramp_last : factor})
      if (std::lround(f * 100) < 1) throw std::invalid_argument("--m220 needs a factor of at least 0.01 (M220 S1)");
  }
}

SpeedStage::SpeedStage(const SpeedOptions& options, const Precision& precision, Diagnostics* diagnostics,
                       LayerSelection* selection)
    : options_(options), precision_(precision), diagnostics_(diagnostics), selection_(selection) {
  options_.validate();
  travel_factor_ = Fixed::from_double(options_.travel_factor);
  if (!options_.mark.empty()) {
    note_restore_ = options_.mark + " restore";
    note_travel_.assign(options_.mark).append(" x").append(number(travel_factor_, kNoteDecimals));
    note_travel_capped_.assign(note_travel_).append(" capped");
  }
  set_factor(Fixed::from_double(options_.ramp ? options_.ramp_first : options_.factor));
}

void SpeedStage::set_factor(Fixed factor) {
  factor_ = factor;
  for (Cache& c : cache_) c.valid = false;
  if (options_.mark.empty()) return;
  note_.assign(options_.mark);
  if (options_.speed > 0) {
    note_.append(" ").append(number_string(options_.speed, 3)).append("mm/s");
  } else {
    note_.append(" x").append(number(factor, kNoteDecimals));
  }
  note_capped_.assign(note_).append(" capped");
}

void SpeedStage::set_enabled(bool on) {
  if (on) {
    stopping_ = false;
    Stage::set_enabled(true);
  } else if (enabled()) {
    // The output may run at a changed speed: stay on until it is back in step.
    stopping_ = changing();
    if (!stopping_) Stage::set_enabled(false);
  }
}

void SpeedStage::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  if (selection_ != nullptr) selection_->enter_layer(info);
  if (options_.ramp) {
    const std::vector<int>& layers = options_.ramp_layers;
    auto it = std::lower_bound(layers.begin(), layers.end(), info.index);
    ramp_layer_ = it != layers.end() && *it == info.index;
    if (ramp_layer_) {
      // Linear from the first layer of the ramp to its last, on exact decimals.
      auto k = static_cast<std::int64_t>(it - layers.begin());
      auto n = static_cast<std::int64_t>(layers.size()) - 1;
      std::int64_t first = Fixed::from_double(options_.ramp_first).units();
      std::int64_t last = Fixed::from_double(options_.ramp_last).units();
      Wide step = n == 0 ? 0 : static_cast<Wide>(last - first) * k;
      std::int64_t units = first + static_cast<std::int64_t>(n == 0 ? 0 : (step + (step < 0 ? -n : n) / 2) / n);
      set_factor(Fixed::from_units(units));
    }
  }
  out.layer(info, before);
}

void SpeedStage::end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) {
  if (selection_ != nullptr) selection_->enter_end_code();
  ramp_layer_ = false;
  out.end_code(info, before);
}

bool SpeedStage::in_region(const TrackedLine& t) {
  if (stopping_) return false;
  if (options_.ramp && !ramp_layer_) return false;
  if (selection_ == nullptr) return true;
  if (!selection_->any()) return t.region == Region::Layer;
  return selection_->selects(t);
}

bool SpeedStage::eligible(const Move& m) const {
  if (m.extruding) return true;
  // Travel in XY only: a move that changes Z is a layer change or a Z-hop,
  // and one that pulls filament back while moving is a wipe (a retraction).
  bool travel = options_.travel || options_.travel_factor > 0;
  return travel && m.travel && m.filament == 0 && !m.z_changed && m.xy_length > 0;
}

void SpeedStage::check_mark(const TrackedLine& t) {
  std::string_view comment = t.line.comment;
  // Any mark but a restore ("; gc-speedup restore ; gc-speedup x2" after a forced run too).
  std::size_t at = comment.find(options_.mark);
  while (at != std::string_view::npos && comment.compare(at, note_restore_.size(), note_restore_) == 0)
    at = comment.find(options_.mark, at + note_restore_.size());
  if (at == std::string_view::npos || !in_region(t)) return;
  throw std::runtime_error("line " + std::to_string(t.raw.number) + ": already changed by " + options_.mark + " ('" +
                           std::string(comment) + "'); changing it again would multiply the factors (give --force to do it)");
}

void SpeedStage::count_layer(int layer) {
  if (stats_.layers.empty() || stats_.layers.back() < layer) stats_.layers.push_back(layer);
}

void SpeedStage::line(const TrackedLine& t, Emitter& out) {
  const Line& line = t.line;
  if (!line.comment.empty() && !options_.force && !options_.mark.empty()) check_mark(t);
  const Move& m = t.move;
  if ((m.kind != MoveKind::Linear && m.kind != MoveKind::Arc) || m.ignored) {
    out.pass(t);
    return;
  }
  if (options_.m220) {
    m220_move(t, out);
  } else {
    feed_move(t, out);
  }
  if (stopping_ && !changing()) {
    stopping_ = false;
    Stage::set_enabled(false);
  }
}

SpeedStage::Target SpeedStage::target_for(const TrackedLine& t) {
  const Move& m = t.move;
  const bool inches = t.state.inches;
  const double unit = inches ? kMmPerInch : 1.0;
  const int decimals = std::min(precision_.of('F') + (inches ? 2 : 0), Fixed::kDecimals);
  // Without a flow cap the target depends on the F alone, and runs of moves
  // share one F: the last answer is reused.
  Cache& cache = cache_[m.extruding ? 0 : 1];
  if (cache.valid && cache.feed == m.feedrate && cache.inches == inches && cache.decimals == decimals &&
      options_.max_flow <= 0)
    return cache.target;
  Target target;
  target.travel = !m.extruding;
  // The original F as the file wrote it (mm/min, or in/min under G20).
  const Fixed original = Fixed::from_double(inches ? m.feedrate / unit : m.feedrate);
  Fixed wanted;
  if (target.travel && options_.travel_factor > 0) {
    wanted = times(original, travel_factor_);
  } else if (options_.speed > 0) {
    wanted = Fixed::from_double(options_.speed * 60 / unit);
  } else {
    wanted = times(original, factor_);
  }
  const bool faster = wanted > original;
  Fixed value = wanted;
  Rounding rounding = Rounding::Nearest;
  if (options_.min_speed > 0) {
    Fixed low = Fixed::from_double(options_.min_speed * 60 / unit);
    if (value < low) {
      value = low;
      rounding = Rounding::Up;
      target.cap = &SpeedStats::capped_min_speed;
    }
  }
  auto cap_above = [&](double mm_per_min, std::uint64_t SpeedStats::*which) {
    Fixed high = Fixed::from_double(mm_per_min / unit);
    if (value > high) {
      value = high;
      rounding = Rounding::Down;
      target.cap = which;
    }
  };
  if (options_.max_speed > 0) cap_above(options_.max_speed * 60, &SpeedStats::capped_max_speed);
  if (options_.max_flow > 0 && m.extruding && m.length > 0) {
    // mm^3/s = filament per mm of path x filament area x mm/s of path.
    double area = std::numbers::pi / 4 * options_.filament_diameter * options_.filament_diameter;
    double per_mm = m.filament / m.length;
    cap_above(options_.max_flow * 60 / (per_mm * area), &SpeedStats::capped_flow);
  }
  // A cap never turns the change around: a move already beyond it keeps its speed.
  if ((faster && value < original) || (!faster && value > original)) {
    value = original;
    rounding = Rounding::Nearest;
  }
  target.word = round_to(value, decimals, rounding);
  target.changed = target.word != original;
  target.feed = target.word.to_double() * unit;
  cache = Cache{true, inches, decimals, m.feedrate, target};
  return target;
}

const std::string& SpeedStage::note_for(bool change, const Target& target) const {
  if (!change) return note_restore_;
  if (target.travel && options_.travel_factor > 0) return target.cap != nullptr ? note_travel_capped_ : note_travel_;
  return target.cap != nullptr ? note_capped_ : note_;
}

void SpeedStage::feed_move(const TrackedLine& t, Emitter& out) {
  const Line& line = t.line;
  const double original = t.state.feedrate;
  const double current = differs_ ? out_feed_ : t.before.feedrate;  // the output's F before this line
  const bool region = in_region(t);
  if (!differs_ && !region) {
    out.pass(t);
    return;
  }
  Target target;
  bool change = region && original > 0 && eligible(t.move);
  if (change) {
    target = target_for(t);
    if (target.cap != nullptr) ++(stats_.*target.cap);
    change = target.changed;
  }
  const double wanted = change ? target.feed : original;
  const Word* f = line.find('F');
  const bool sets_feed = f != nullptr && f->has_value && f->value() > 0;
  double result = sets_feed ? original : current;  // the output's F after the line as it is
  if (wanted != result) {
    bool editable = !line.has_line_number && !line.has_checksum && !line.malformed && (f == nullptr || f->has_value);
    if (editable) {
      if (!change) {
        // Back to the original F, written exactly as the file had it.
        target.word = Fixed::from_double(t.state.inches ? original / kMmPerInch : original);
        ++stats_.restores;
      }
      LineEdit edit(line);
      edit.set('F', target.word, Fixed::kDecimals);
      if (!options_.mark.empty()) edit.note(note_for(change, target));
      out.replace(t, edit.text());
      ++stats_.lines_edited;
      result = wanted;
    } else {
      ++stats_.left_alone;
      change = false;
      if (!warned_edit_ && diagnostics_ != nullptr) {
        warned_edit_ = true;
        diagnostics_->warn(t.raw.number,
                           "a line with a line number, checksum or bare F cannot be edited; its speed is left as it "
                           "is (warned once)");
      }
      out.pass(t);
    }
  } else {
    out.pass(t);
  }
  if (change) {
    ++stats_.moves_changed;
    if (t.region == Region::Layer) count_layer(t.layer);
  }
  differs_ = result != original;
  out_feed_ = result;
}

void SpeedStage::m220_move(const TrackedLine& t, Emitter& out) {
  bool region = in_region(t);
  int wanted = region ? static_cast<int>(std::lround(factor_.to_double() * 100)) : 100;
  if (wanted != m220_percent_) {
    std::string note;
    if (!options_.mark.empty()) note = " ; " + (wanted == 100 ? note_restore_ : note_);
    bool backup = options_.m220_restore == M220Restore::Backup;
    if (m220_percent_ == 100 && backup) {
      out.insert("M220 B" + note);
      ++stats_.m220_lines;
    }
    if (wanted == 100 && backup) {
      out.insert("M220 R" + note);
    } else {
      out.insert("M220 S" + std::to_string(wanted) + note);
    }
    ++stats_.m220_lines;
    m220_percent_ = wanted;
  }
  out.pass(t);
  if (region && wanted != 100) {
    ++stats_.moves_changed;
    if (t.region == Region::Layer) count_layer(t.layer);
  }
}

void SpeedStage::finish(Emitter& out) {
  if (m220_percent_ == 100) return;
  std::string note = options_.mark.empty() ? std::string() : " ; " + note_restore_;
  out.insert((options_.m220_restore == M220Restore::Backup ? "M220 R" : "M220 S100") + note);
  ++stats_.m220_lines;
  m220_percent_ = 100;
}

}  // namespace gcode
