#pragma once
// Pacing (SenderConfig::pace): hold no more moves ahead of the nozzle than
// the printer's planner takes. A move goes out only while the moves in
// flight and those the planner still holds are fewer than its blocks. What
// the planner holds comes from the answers: each answered move entered it
// then, and runs for its length at its feed rate after the one before (the
// fastest it can go, so the count never runs high and the planner is never
// starved by it).
//
// Open-loop for now: the pace is the file's own (length / feed rate); a
// pacer that learns the printer's pace from the answers' timing goes here.
#include <array>
#include <cstddef>

namespace gcode::serial {

class Pacer {
 public:
  static constexpr double kNever = 1e300;

  // Whether a move must wait: `moves_in_flight` sent and not answered, with
  // a planner of `planner_blocks`. When it must and nothing is in flight (no
  // answer will come), wake() says when a block ends.
  bool blocked(double now, int moves_in_flight, int planner_blocks);
  // An answered move of `nominal` printer seconds entered the planner.
  void planned(double nominal, double now, int planner_blocks, double time_scale);
  // When a blocked move may go (kNever: with an answer).
  double wake() const { return wake_; }
  void clear_wake() { wake_ = kNever; }

 private:
  std::size_t blocks(int planner_blocks) const;

  // When the last answered moves end at the earliest (a ring of the planner's size).
  std::array<double, 64> ends_{};
  std::size_t next_ = 0;
  double last_end_ = 0;
  double wake_ = kNever;
};

}  // namespace gcode::serial
