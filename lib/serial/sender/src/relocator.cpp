#include "gcode/serial/sender/relocator.hpp"

namespace gcode::serial {

long long Relocator::probe(double now, long long highest_sent) {
  phase_ = Phase::Probing;
  since_ = now;
  position_asked_ = false;
  return highest_sent + 2;
}

Relocator::Refusal Relocator::refused(long long expected, long long last_acked, long long highest_sent, double now) {
  const long long last = expected - 1;
  // It restarted while the port was away, its greeting lost with the link.
  if (last == 0 && highest_sent > 0) return Refusal::Restarted;
  if (last < last_acked || last > highest_sent) return Refusal::Impossible;
  phase_ = Phase::Locating;
  line_ = last;
  since_ = now;
  return Refusal::Took;
}

Relocator::Ok Relocator::ok() {
  if (phase_ == Phase::Finishing) {
    phase_ = Phase::None;
    return Ok::Done;
  }
  if (position_asked_) return Ok::Wait;
  position_asked_ = true;
  return Ok::AskPosition;
}

}  // namespace gcode::serial
