#include "gcode/serial/protocol/probe_credit.hpp"

#include <algorithm>

namespace gcode::serial {

int ProbeCredit::answered(bool room, bool wanted, int planner_blocks) {
  const bool waited = full_;
  full_ = false;
  const int blocks = std::max(1, planner_blocks);
  if (!room) {
    size_ = 1;
    left_ = 0;
    lead_ = 0;
    return 0;
  }
  // Room, but the printer does not run dry between probes: one move, as
  // at the file's pace; the size stays for when it does.
  if (!wanted) return 0;
  // (Added to those of the probe before that are still left: it went
  // before them.)
  const int more = size_ - 1;
  left_ = std::min(left_ + more, blocks - 1);
  lead_ = left_ / 4;
  // A move ahead of it waited for a block, yet it found room: as many as
  // last time, no more.
  if (!waited) size_ = std::min(2 * size_, blocks);
  return more;
}

void ProbeCredit::full() {
  // No more now; the probe behind it says whether the planner was full
  // (Marlin holds it then): a move's lateness is the host's timing too.
  full_ = true;
  left_ = 0;
  lead_ = 0;
}

bool ProbeCredit::take() {
  if (left_ == 0) return false;
  --left_;
  return true;
}

}  // namespace gcode::serial
