// A print that gc-send --resume finds paused in its journal goes back into
// the pause: the block is not sent again (the printer ran it, or a reset's
// resume sequence took the nozzle to where it left it), the print waits for
// `resume`, and the resume's way back is the one the pause block has for the
// point where the print stopped, from where the printer stands.
#include <fmt/format.h>

#include "gcode/serial/print_control.hpp"

namespace gcode::serial {

void PrintControl::resume_into_pause(const MachineState& at, const MachineState& parked, double retracted,
                                     double top_z) {
  PauseRecord& r = start_record("the journal's pause");
  PauseConfig c = pause_config(at);
  // Parked where it stands: the block's way back starts there.
  c.park = true;
  c.park_x = parked.position[kX];
  c.park_y = parked.position[kY];
  PauseBlock block = build_pause(PausePoint{at, retracted, top_z, &precision_}, c);
  MachineState block_end = at;
  for (const std::string& l : block.pause) track(l, block_end);
  r.input_line = last_source_;
  r.block_number = sender_.last_submitted() + 1;
  r.block = true;
  handed_ = at;
  stop_at(at, block_end, true);
  stop_.printer = parked;
  stop_.resume_lines = std::move(block.resume);
  diag_.info("the print was paused: waiting for resume");
}

}  // namespace gcode::serial
