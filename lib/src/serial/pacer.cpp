#include "gcode/serial/pacer.hpp"

#include <algorithm>

namespace gcode::serial {

std::size_t Pacer::blocks(int planner_blocks) const {
  return std::min(ends_.size(), static_cast<std::size_t>(std::max(1, planner_blocks)));
}

bool Pacer::blocked(double now, int moves_in_flight, int planner_blocks) {
  const std::size_t n = blocks(planner_blocks);
  int ahead = 0;
  double first_end = kNever;
  for (std::size_t i = 0; i < n; ++i) {
    if (ends_[i] > now) {
      ++ahead;
      first_end = std::min(first_end, ends_[i]);
    }
  }
  bool blocked = moves_in_flight + ahead >= static_cast<int>(n);
  // With nothing in flight no answer will come: wake when a block ends.
  wake_ = blocked && moves_in_flight == 0 ? first_end : kNever;
  return blocked;
}

void Pacer::planned(double nominal, double now, int planner_blocks, double time_scale) {
  const std::size_t n = blocks(planner_blocks);
  double scale = time_scale > 0 ? time_scale : 1;
  last_end_ = std::max(last_end_, now) + nominal / scale;
  ends_[next_ % n] = last_end_;
  next_ = (next_ + 1) % n;
}

}  // namespace gcode::serial
