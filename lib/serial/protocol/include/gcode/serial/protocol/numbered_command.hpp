#pragma once
// What the sender tells the journal (send_journal.hpp) as a numbered command
// first goes out, before its bytes can reach the port: enough to put the
// printer back after that command later (a resume).
#include <cstdint>

#include "gcode/core/machine_state.hpp"
#include "gcode/serial/protocol/reset_sequence.hpp"

namespace gcode::serial {

struct NumberedCommand {
  long long n = 0;
  std::uint64_t source_line = 0;  // 0: a line of gc-send's own
  int layer = 0;
  const MachineState* after = nullptr;
  const ResumeTrack* track = nullptr;  // the print up to it, for a resume after a reset
  long long restore = 0;  // a line of such a resume: the command it goes back to (else 0)
  bool closing = false;   // the closing M400, numbered once every input line was
  bool drains = false;    // M400, G28, G29, G4: once it is answered, every command up to it ran
  // A line of the sender's own that changes nothing (an M105 question, a
  // pace probe): its point is the command's before it.
  bool repeat = false;
};

}  // namespace gcode::serial
