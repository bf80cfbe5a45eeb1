#pragma once
// When an answer from the printer is overdue: a model of the link and of the
// printer's planner, fed with what the sender writes and what comes back, in
// the sender's (wall clock) seconds.
//
// Marlin answers a command with "ok" when the command leaves its queue: a
// move when it gets a planner block, a command that waits for the moves
// (M400) when the planner is empty, most others at once. So the answer to a
// line in flight cannot come before
//   * the line has crossed the link: its bytes at baud/10 bytes per second
//     after whatever was written before it (time_scale: a simulated printer
//     runs that much faster than the wall clock);
//   * the answer before it came: the firmware runs commands in order;
//   * for a move, the planner has room for it and the moves ahead of it: a
//     planner of `planner_blocks` blocks has room when the block that many
//     moves back has ended. The model keeps the end times of the last moves
//     from their estimated times, chained from the moment each "ok" came;
//     since a move is only answered when its block fits, an answer that
//     comes sooner than the model says pulls the model's end times back to
//     it. The estimates are scaled by how fast this printer turns out to be:
//     while the planner is full, the time between two answered moves is
//     what the block that left took, and the last 16 such times against
//     their estimates give the scale (1.25 times it, at most 1.5, the value
//     it starts from), but a move never takes less than its length at its
//     feed rate;
//   * for any other command, the planner is empty (some wait for it).
// Once that has passed, plus a margin for the host's own latency, the
// answer's bytes and estimates that run short, the answer is overdue: a lost
// "ok" costs about that margin instead of a whole --timeout.
//
// Commands of unknown length (heating, homing, probing, waiting for the
// user) cannot be bounded that way; Marlin reports "busy: processing" (every
// 2 s) or temperatures (every second) while it runs them, and the model
// expects the next sign of life within 1.5 of those intervals.
#include <array>
#include <cstddef>

namespace gcode::serial {

class AnswerClock {
 public:
  static constexpr double kMargin = 0.1;          // seconds: host and adapter latency
  static constexpr double kMotionFactor = 1.5;    // the most the estimates are scaled by (slow printers)
  static constexpr double kMinFactor = 0.02;      // the least (moves that take no time)
  static constexpr std::size_t kSamples = 16;     // answered moves that measure the printer's speed
  static constexpr double kKeepalive = 2.0;       // printer seconds: Marlin's DEFAULT_KEEPALIVE_INTERVAL
  static constexpr std::size_t kMaxPlanner = 64;

  // bytes_per_second: baud / 10 times the time scale, 0 when unknown (a
  // pseudo-terminal: bytes cross at once).
  AnswerClock(double bytes_per_second, double time_scale, int planner_blocks = 16);
  void set_link(double bytes_per_second, double time_scale);
  void set_planner_blocks(int blocks);

  double byte_time() const { return byte_time_; }
  double time_scale() const { return scale_; }

  // `bytes` were handed to the port at `now`; returns when the last of them
  // reaches the printer.
  double written(std::size_t bytes, double now);
  // When the byte `back` bytes before the last one written arrives.
  double arrival_of(std::size_t back) const { return wire_free_ - static_cast<double>(back) * byte_time_; }

  // An "ok" acknowledged a command at `now`; a move of `motion` estimated
  // printer-seconds (0 for a command without motion), at least `nominal`
  // (its length at its feed rate), entered the planner with it.
  void answered(double motion, double now, double nominal = 0);
  // "busy:" or a temperature report while a long command runs.
  void keepalive(double now);

  // What the printer must have done before it can answer a command.
  struct Wait {
    int moves = 0;             // moves that must fit into the planner: the command's own and those ahead
    double motion = 0;         // printer seconds of the moves ahead of it in flight
    bool empty = false;        // the planner must be empty (a command that is not a move)
    bool unbounded = false;    // a command of unknown length: the next sign of life
  };
  // The earliest time the answer to a command that reached the printer at
  // `arrival` can come, without the margin.
  double ready(double arrival, const Wait& wait) const;
  // When that answer is overdue.
  double due(double arrival, const Wait& wait) const;
  // How long the link must stay quiet after `bytes` stale bytes were on the
  // way before no more of them can be answered.
  double quiet(std::size_t bytes) const;
  double margin() const;
  double last_answer() const { return last_answer_; }
  double last_keepalive() const { return last_keepalive_; }
  // When the planner is empty, as far as the answers tell.
  double planner_empty() const { return last_end_; }
  // Answered moves the model says have not ended by `now` (at most the
  // planner's size): what the planner holds, as far as the answers tell.
  int moves_ahead(double now) const {
    int n = 0;
    for (std::size_t i = 0; i < count_; ++i) n += ends_[i] > now ? 1 : 0;
    return n;
  }
  int planner_blocks() const { return static_cast<int>(planner_); }
  // What the moves' estimated times are scaled by now.
  double motion_factor() const { return factor_; }

 private:
  double byte_time_ = 0;       // wall seconds per byte, 0 = unlimited
  double scale_ = 1;
  std::size_t planner_ = 16;
  double wire_free_ = 0;       // when the last byte written reaches the printer
  double last_answer_ = -1e300;
  double last_keepalive_ = -1e300;
  double keepalive_interval_ = 0;  // measured, wall seconds; 0 = none seen yet
  // End times of the last `planner_` moves answered, oldest at ends_[next_]
  // once `count_` reaches `planner_`.
  std::array<double, kMaxPlanner> ends_{};
  std::array<double, kMaxPlanner> estimates_{};  // their estimated times, printer seconds
  std::size_t next_ = 0;
  std::size_t count_ = 0;
  double last_end_ = -1e300;
  double last_move_answer_ = 0;
  double factor_ = kMotionFactor;
  // Measured block times (wall seconds times the scale) against their estimates.
  std::array<double, kSamples> taken_{};
  std::array<double, kSamples> estimated_{};
  std::size_t sample_next_ = 0;
  std::size_t samples_ = 0;
};

}  // namespace gcode::serial
