#include "gcode/report/estimator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace gcode {

namespace {

constexpr double kTiny = 1e-9;
// Marlin's feed rate before any F word: feedrate_mm_s = 25 mm/s (1500 mm/min).
constexpr double kDefaultFeed = 25;

// Seconds for `length` mm entered at v0, left at v1, cruising at most at vn,
// with acceleration a: the trapezoid, or the triangle when the move is too
// short to reach vn. The planner guarantees v0, v1 <= vn and that v1 is
// reachable from v0 within the length.
double trapezoid_time(double length, double v0, double v1, double vn, double a) {
  if (length <= 0) return 0;
  if (vn <= kTiny) return 0;
  if (a <= kTiny) return length / vn;
  double inv_a = 1 / a;
  double accel_dist = (vn * vn - v0 * v0) * 0.5 * inv_a;
  double decel_dist = (vn * vn - v1 * v1) * 0.5 * inv_a;
  if (accel_dist + decel_dist <= length) return (2 * vn - v0 - v1) * inv_a + (length - accel_dist - decel_dist) / vn;
  double peak = std::sqrt(a * length + (v0 * v0 + v1 * v1) * 0.5);
  if (peak < std::max(v0, v1)) return 2 * length / (v0 + v1);  // rounding: a plain ramp
  return (2 * peak - v0 - v1) * inv_a;
}

// The speed reachable from v over `length` mm at acceleration a.
double reachable(double v, double a, double length) { return std::sqrt(v * v + 2 * a * length); }

}  // namespace

std::string format_duration(double seconds) {
  long long s = std::llround(std::max(0.0, seconds));
  return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
}

Estimator::Estimator(const EstimatorOptions& options, TimeSink* sink)
    : options_(options), limits_(options.limits), sink_(sink) {
  ring_.resize(static_cast<std::size_t>(std::max(2, options_.lookahead)));
  hotend_temp_ = hotend_target_ = options_.ambient;
  bed_temp_ = bed_target_ = options_.ambient;
}

void Estimator::add(const Line& line, const Move& move) {
  if (line.kind != CommandKind::Standard) return;
  if (line.letter == 'M') {
    if (options_.file_limits && limits_.apply(line)) return;
    switch (line.number) {
      case 220:  // feed rate percentage; Marlin 2 and Prusa firmware: B backs it up, R restores it
        if (line.has('B')) feed_backup_ = feed_percent_;
        if (line.has('R')) feed_percent_ = feed_backup_;
        if (const Word* s = line.find('S'); s != nullptr && s->has_value && s->value() > 0) feed_percent_ = s->value();
        return;
      case 104: case 109: heat_wait(line, false); return;
      case 140: case 190: case 191: heat_wait(line, true); return;
      case 400: drain(); return;
      default: return;
    }
  }
  if (line.letter != 'G') return;
  if (line.number == 4 && line.subcode < 0) {
    // G4 P<ms> or S<s>; Marlin waits for the moves before it to finish.
    double seconds = line.value_or('S', 0) + line.value_or('P', 0) / 1000;
    drain();
    account_wait(&TimeBreakdown::dwell, std::max(0.0, seconds));
    return;
  }
  switch (move.kind) {
    case MoveKind::Linear:
    case MoveKind::Arc:
      if (!move.ignored) add_move(move);
      return;
    case MoveKind::Home:
      drain();
      account_wait(&TimeBreakdown::home, options_.home_time);
      return;
    case MoveKind::FirmwareRetract:
    case MoveKind::FirmwareUnretract: {
      bool retract = move.kind == MoveKind::FirmwareRetract;
      double length = limits_.fw_retract_length + (retract ? 0 : limits_.fw_unretract_extra);
      if (length <= kTiny) return;
      Move m;
      m.kind = MoveKind::Linear;
      m.filament = retract ? -length : length;
      m.feedrate = (retract ? limits_.fw_retract_speed : limits_.fw_unretract_speed) * 60;
      // M220 does not scale firmware retraction: undo it in advance.
      m.feedrate *= 100 / feed_percent_;
      add_move(m);
      return;
    }
    default:
      return;
  }
}

void Estimator::add_move(const Move& move) {
  std::array<double, 4> delta{move.end[kX] - move.start[kX], move.end[kY] - move.start[kY],
                              move.end[kZ] - move.start[kZ], move.filament};
  double length = move.length;
  bool e_only = length <= kTiny;
  if (e_only) {
    length = std::fabs(delta[3]);
    if (length <= kTiny) return;
    delta[0] = delta[1] = delta[2] = 0;
  } else if (move.kind == MoveKind::Arc) {
    // The path is the arc's XY length with its own Z: the XY chord gives the
    // direction in the plane. A circle back to its start (BambuStudio's
    // spiral lift "G3 Z.6 I1.217 J0 P1") has no XY chord: its XY travel goes
    // on X, so a helix is never timed as a Z move at the Z feed rate.
    double chord_xy = std::sqrt(delta[0] * delta[0] + delta[1] * delta[1]);
    if (chord_xy > kTiny) {
      delta[0] *= move.xy_length / chord_xy;
      delta[1] *= move.xy_length / chord_xy;
    } else {
      delta[0] = move.xy_length;
      delta[1] = 0;
    }
  }
  Kind kind = e_only ? Kind::Retract : (move.filament > 0 ? Kind::Print : Kind::Travel);

  double nominal = (move.feedrate > 0 ? move.feedrate / 60 : kDefaultFeed) * feed_percent_ / 100;
  nominal = std::max(nominal, kind == Kind::Travel ? limits_.min_travel_feedrate : limits_.min_feedrate);

  // Marlin: an E-only block uses the retract acceleration, any other block
  // with E the print acceleration, a block without E the travel one
  // (RepRapFirmware has no retract acceleration).
  double accel = e_only ? (limits_.firmware == Firmware::Marlin ? limits_.retract_acceleration
                                                                 : limits_.print_acceleration)
                        : (delta[3] != 0 ? limits_.print_acceleration : limits_.travel_acceleration);

  std::array<double, 4> axis_speed{};
  std::array<double, 4> unit{};
  double speed_factor = 1;
  double inv_length = 1 / length;
  for (std::size_t a = 0; a < 4; ++a) {
    double ratio = delta[a] * inv_length;
    double r = std::fabs(ratio);
    if (r > kTiny) {
      if (nominal * r > limits_.max_feedrate[a] && limits_.max_feedrate[a] > 0)
        speed_factor = std::min(speed_factor, limits_.max_feedrate[a] / (nominal * r));
      if (accel * r > limits_.max_acceleration[a] && limits_.max_acceleration[a] > 0)
        accel = limits_.max_acceleration[a] / r;
    }
    axis_speed[a] = nominal * ratio;
    if (a < 3 || e_only) unit[a] = ratio;
  }
  nominal *= speed_factor;
  for (double& s : axis_speed) s *= speed_factor;

  // The speed from which every axis may stop at once (classic jerk).
  double safe = nominal;
  for (std::size_t a = 0; a < 4; ++a) {
    double s = std::fabs(axis_speed[a]);
    if (s > limits_.jerk[a]) safe = std::min(safe, nominal * limits_.jerk[a] / s);
  }

  Block b{};
  b.length = length;
  b.nominal = nominal;
  b.accel = accel;
  b.kind = kind;
  b.tag = tag_;
  b.max_entry = junction_speed(axis_speed, nominal, accel, safe, unit);
  b.exit_limit = limits_.junction_deviation > 0 ? 0 : safe;
  b.entry = std::min(b.max_entry, reachable(b.exit_limit, accel, length));

  have_previous_ = true;
  previous_axis_speed_ = axis_speed;
  previous_unit_ = unit;
  previous_nominal_ = nominal;
  previous_safe_ = safe;
  ++blocks_;
  push_block(b);
}

double Estimator::junction_speed(const std::array<double, 4>& axis_speed, double nominal, double accel, double safe,
                                 const std::array<double, 4>& unit) const {
  if (limits_.junction_deviation > 0) {
    // Marlin 2: the junction is a circular arc that deviates by at most J
    // from the corner; its speed is what the acceleration allows on that arc.
    if (!have_previous_) return 0;
    double cos_theta = 0;
    for (std::size_t a = 0; a < 4; ++a) cos_theta -= previous_unit_[a] * unit[a];
    double v;
    if (cos_theta > 0.999999) {
      v = 0;  // a full reversal
    } else if (cos_theta < -0.999999) {
      v = nominal;  // straight on
    } else {
      double sin_half = std::sqrt(0.5 * (1 - cos_theta));
      v = std::sqrt(accel * limits_.junction_deviation * sin_half / (1 - sin_half));
    }
    return std::min({v, nominal, previous_nominal_});
  }

  // Classic jerk (Marlin 1.1 planner): start from the smaller nominal speed
  // and scale it down until no axis changes speed by more than its jerk.
  if (!have_previous_ || previous_nominal_ <= 1e-4) return safe;
  bool previous_larger = previous_nominal_ > nominal;
  double smaller_factor = previous_larger ? nominal / previous_nominal_ : previous_nominal_ / nominal;
  double v = previous_larger ? nominal : previous_nominal_;
  double factor = 1;
  bool limited = false;
  for (std::size_t a = 0; a < 4; ++a) {
    double v_exit = previous_axis_speed_[a];
    double v_entry = axis_speed[a];
    if (previous_larger) v_exit *= smaller_factor;
    if (limited) {
      v_exit *= factor;
      v_entry *= factor;
    }
    // Coasting in one direction costs the difference; a reversal costs the larger speed.
    double jerk = v_exit > v_entry ? ((v_entry > 0 || v_exit < 0) ? v_exit - v_entry : std::max(v_exit, -v_entry))
                                   : ((v_entry < 0 || v_exit > 0) ? v_entry - v_exit : std::max(-v_exit, v_entry));
    if (jerk > limits_.jerk[a]) {
      factor *= limits_.jerk[a] / jerk;
      limited = true;
    }
  }
  if (limited) v *= factor;
  // Both moves may start and stop faster than the junction allows: the
  // machine gets through it at the safe speed anyway.
  if (previous_safe_ > v * 0.99 && safe > v * 0.99) v = safe;
  return std::min({v, nominal, previous_nominal_});
}

void Estimator::push_block(const Block& b) {
  std::size_t capacity = ring_.size();
  if (count_ == capacity) finalize_front();
  if (count_ == 0) front_entry_ = b.max_entry;
  ring_[(head_ + count_) % capacity] = b;
  ++count_;
  // Backward pass: the new block ends at its stop speed; each block before it
  // may enter only as fast as it can still slow down to its successor's
  // entry. Stop where nothing changes: the blocks before are unaffected.
  for (std::size_t i = count_ - 1; i-- > 0;) {
    Block& cur = ring_[(head_ + i) % capacity];
    const Block& next = ring_[(head_ + i + 1) % capacity];
    double entry = std::min(cur.max_entry, reachable(next.entry, cur.accel, cur.length));
    if (std::fabs(entry - cur.entry) <= 1e-12 * (1 + entry)) break;
    cur.entry = entry;
  }
}

void Estimator::finalize_front() {
  std::size_t capacity = ring_.size();
  const Block& b = ring_[head_];
  // Forward pass for the oldest block: its entry is final; its exit is the
  // next block's planned entry unless this block cannot accelerate to it.
  double v_in = std::min(front_entry_, b.entry);
  double v_out = count_ > 1 ? ring_[(head_ + 1) % capacity].entry : b.exit_limit;
  v_out = std::min(v_out, reachable(v_in, b.accel, b.length));
  double t = trapezoid_time(b.length, v_in, v_out, b.nominal, b.accel);
  account(b, t);
  front_entry_ = v_out;
  head_ = (head_ + 1) % capacity;
  --count_;
}

void Estimator::drain() {
  while (count_ > 0) finalize_front();
  have_previous_ = false;
}

void Estimator::finish() { drain(); }

double Estimator::queued() const {
  std::size_t capacity = ring_.size();
  double t = 0;
  double v_in = count_ > 0 ? std::min(front_entry_, ring_[head_].entry) : 0;
  for (std::size_t i = 0; i < count_; ++i) {
    const Block& b = ring_[(head_ + i) % capacity];
    double v_out = i + 1 < count_ ? ring_[(head_ + i + 1) % capacity].entry : b.exit_limit;
    v_out = std::min(v_out, reachable(v_in, b.accel, b.length));
    t += trapezoid_time(b.length, v_in, v_out, b.nominal, b.accel);
    v_in = v_out;
  }
  return t;
}

void Estimator::add_wait(double seconds) {
  drain();
  account_wait(&TimeBreakdown::dwell, std::max(0.0, seconds));
}

void Estimator::heat_wait(const Line& line, bool bed) {
  const Word* s = line.find('S');
  const Word* r = line.find('R');
  const Word* target_word = (s != nullptr && s->has_value) ? s : ((r != nullptr && r->has_value) ? r : nullptr);
  if (target_word == nullptr) return;
  double target = target_word->value();
  double& temp = bed ? bed_temp_ : hotend_temp_;
  double& old_target = bed ? bed_target_ : hotend_target_;
  double& since = bed ? bed_since_ : hotend_since_;
  double rate = bed ? options_.bed_heat_rate : options_.hotend_heat_rate;
  bool wait = line.number == 109 || line.number == 190 || line.number == 191;
  if (wait) drain();
  // Where the temperature got to while the machine did other things.
  double now = elapsed_ + (wait ? 0 : queued());
  double moved = std::max(0.0, now - since) * rate;
  temp = old_target > temp ? std::min(old_target, temp + moved) : std::max(old_target, temp - moved);
  old_target = target;
  since = now;
  // M109 S waits only while heating; R (and a bed M190 R) also while cooling.
  if (wait && rate > 0 && (target > temp || (target_word == r && target < temp))) {
    double seconds = std::fabs(target - temp) / rate;
    temp = target;
    if (options_.heat_time) account_wait(&TimeBreakdown::heat, seconds);
    since = elapsed_;
  }
}

void Estimator::account(const Block& b, double seconds) {
  elapsed_ += seconds;
  switch (b.kind) {
    case Kind::Print: breakdown_.print += seconds; break;
    case Kind::Travel: breakdown_.travel += seconds; break;
    case Kind::Retract: breakdown_.retract += seconds; break;
  }
  if (sink_ != nullptr) sink_->on_motion(b.tag, seconds, b.nominal > kTiny ? b.length / b.nominal : 0.0);
}

void Estimator::account_wait(double TimeBreakdown::*field, double seconds) {
  elapsed_ += seconds;
  breakdown_.*field += seconds;
  if (sink_ != nullptr) sink_->on_time(tag_, seconds);
}

}  // namespace gcode
