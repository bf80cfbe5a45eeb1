#include "gcode/serial/probe_credit.hpp"

#include <algorithm>

namespace gcode::serial {

int ProbeCredit::answered(bool room, bool grow, int planner_blocks) {
  // A move ahead of the probe waited for a block: the probe's quick answer
  // lets no more go this time.
  grow = grow && !full_;
  full_ = false;
  const int blocks = std::max(1, planner_blocks);
  if (!room) {
    size_ = 1;
    left_ = 0;
    lead_ = 0;
    return 0;
  }
  // (Added to those of the probe before that are still left: it went
  // before them.)
  // Room, but the printer does not run dry between probes: one move, as
  // at the file's pace; the size stays for when it does.
  const int more = grow ? size_ - 1 : 0;
  left_ = std::min(left_ + more, blocks - 1);
  lead_ = left_ / 4;
  if (grow) size_ = std::min(2 * size_, blocks);
  return more;
}

void ProbeCredit::full() {
  // Halved, not back to one: a move's lateness is the host's timing too,
  // and the probe behind it (held by a full planner) says the rest.
  full_ = true;
  size_ = std::max(1, size_ / 2);
  left_ = 0;
  lead_ = 0;
}

bool ProbeCredit::take() {
  if (left_ == 0) return false;
  --left_;
  return true;
}

}  // namespace gcode::serial
