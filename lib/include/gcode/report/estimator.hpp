#pragma once
// Print-time estimate: a model of the firmware's motion planner, fed line by
// line as the G-code streams.
//
// Each move becomes a block with a trapezoidal speed profile (accelerate,
// cruise, decelerate) under the machine limits (planner_limits.hpp): its
// nominal speed is F (times M220) capped per axis by the max feed rates, its
// acceleration is the print, travel or retract acceleration (M204) capped per
// axis by M201. The speed at each junction is limited by classic jerk (M205
// X Y Z E, as Marlin 1.x, Prusa firmware and PrusaSlicer's estimator) or by
// junction deviation (M205 J, Marlin 2). A backward pass lowers each junction
// so the moves after it can still stop; a forward pass lowers it to what the
// moves before it can reach. Both run over a bounded window of blocks (the
// look-ahead), so memory is constant: the oldest block's profile is final
// once `lookahead` blocks follow it, exactly as the firmware commits to the
// block it executes.
//
// Waits are not motion: G4 dwells, M109/M190/M191 heating (from a heat rate,
// or left out), G28 (a fixed cost). They, and M400, empty the planner (the
// machine stops) before their time is counted.
//
// Time is reported per tag: the caller sets a tag (a layer number, a line
// number) before feeding a line; when a block's time is final it is added to
// the sink under the tag that was current when its line came in.
//
// Time remaining from a point (gc-send's ETA): run once over the file for the
// total, then while printing, remaining = total - elapsed() of a second
// estimator fed the lines sent so far (plus its queued() if the moves in the
// look-ahead should count as done).
#include <cstdint>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/report/planner_limits.hpp"
#include "gcode/core/machine_state.hpp"

namespace gcode {

struct EstimatorOptions {
  PlannerLimits limits;             // starting limits (defaults, profile, options)
  bool file_limits = true;          // obey M201/M203/M204/M205/M566 in the G-code
  bool heat_time = true;            // count heating waits
  double hotend_heat_rate = 2.0;    // degrees C per second
  double bed_heat_rate = 0.5;       // degrees C per second
  double ambient = 25;              // degrees C at the start
  double home_time = 10;            // seconds per G28
  int lookahead = 64;               // blocks planned ahead (Marlin: 16; PrusaSlicer's model: 64)
};

// Time spent per kind of activity, seconds.
struct TimeBreakdown {
  double print = 0;    // extruding moves
  double travel = 0;   // moves without extrusion
  double retract = 0;  // E-only moves, firmware retraction
  double dwell = 0;    // G4
  double heat = 0;     // M109 / M190 / M191 waits
  double home = 0;     // G28
  double total() const { return print + travel + retract + dwell + heat + home; }
};

class TimeSink {
 public:
  virtual ~TimeSink() = default;
  // `seconds` of the line(s) fed under `tag` are now final.
  virtual void on_time(std::int64_t tag, double seconds) = 0;
  // A move's `seconds` are final; `cruise_seconds` of them it would take at
  // its nominal speed all the way (the rest is lost to acceleration). Waits
  // come through on_time only.
  virtual void on_motion(std::int64_t tag, double seconds, double cruise_seconds) {
    (void)cruise_seconds;
    on_time(tag, seconds);
  }
};

class Estimator {
 public:
  explicit Estimator(const EstimatorOptions& options = {}, TimeSink* sink = nullptr);

  // The tag for the lines fed from now on.
  void set_tag(std::int64_t tag) { tag_ = tag; }
  // Feeds one line and what the machine state made of it (MachineState::apply).
  void add(const Line& line, const Move& move);
  // A move alone (no limit commands, no waits): for callers that build moves.
  void add_move(const Move& move);
  // Extra time that stops the machine first (a dwell the caller knows of).
  void add_wait(double seconds);
  // End of input: the last moves decelerate to a stop and become final.
  void finish();

  // Seconds of the blocks already final.
  double elapsed() const { return elapsed_; }
  // Seconds of the blocks still in the look-ahead, planned as if the machine
  // stopped after the last one.
  double queued() const;
  // elapsed() + queued(): the best estimate of the time so far.
  double total() const { return elapsed_ + queued(); }
  const TimeBreakdown& breakdown() const { return breakdown_; }
  const PlannerLimits& limits() const { return limits_; }
  std::uint64_t blocks() const { return blocks_; }

 private:
  enum class Kind : std::uint8_t { Print, Travel, Retract };
  struct Block {
    double length;       // mm along the path (|E| for E-only moves)
    double nominal;      // mm/s
    double accel;        // mm/s^2
    double max_entry;    // junction limit, mm/s
    double entry;        // planned entry speed (backward pass), mm/s
    double exit_limit;   // speed the block may end at if it is the last: a full stop (jerk: its safe speed)
    std::int64_t tag;
    Kind kind;
  };

  void push_block(const Block& b);
  void finalize_front();
  void drain();
  double junction_speed(const std::array<double, 4>& axis_speed, double nominal, double accel, double safe,
                        const std::array<double, 4>& unit) const;
  void heat_wait(const Line& line, bool bed);
  void account(const Block& b, double seconds);
  void account_wait(double TimeBreakdown::*field, double seconds);

  EstimatorOptions options_;
  PlannerLimits limits_;
  TimeSink* sink_;
  std::int64_t tag_ = 0;
  double feed_percent_ = 100;
  double feed_backup_ = 100;  // M220 B

  // Look-ahead ring: blocks [head_, head_ + count_) modulo capacity.
  std::vector<Block> ring_;
  std::size_t head_ = 0;
  std::size_t count_ = 0;
  double front_entry_ = 0;  // the final entry speed of the oldest block

  // The previous block, for the junction.
  bool have_previous_ = false;
  std::array<double, 4> previous_axis_speed_{};
  std::array<double, 4> previous_unit_{};
  double previous_nominal_ = 0;
  double previous_safe_ = 0;

  // Heating model: a temperature that approaches its target at a fixed rate.
  double hotend_temp_ = 25, hotend_target_ = 25, hotend_since_ = 0;
  double bed_temp_ = 25, bed_target_ = 25, bed_since_ = 0;

  double elapsed_ = 0;
  TimeBreakdown breakdown_;
  std::uint64_t blocks_ = 0;
};

// Formats seconds as h:mm:ss (rounded to the second).
std::string format_duration(double seconds);

}  // namespace gcode
