#include "gcode/serial/protocol/resend.hpp"

namespace gcode::serial {

ResendState::Verdict ResendState::request(long long n, int max_resends) {
  // Line n is already being resent: this is a line that was on the wire
  // behind the bad one and failed too (Marlin empties its buffer after an
  // error, so each such line draws its own Error, Resend and ok).
  if (settling_ && n == line_) return Verdict::Repeat;
  if (n == asked_) {
    if (++count_ > max_resends) return Verdict::TooMany;
  } else {
    asked_ = n;
    count_ = 1;
  }
  return Verdict::Rewind;
}

}  // namespace gcode::serial
