// A print that gc-send --resume finds paused in its journal goes back into
// the pause: the block is not sent again (the printer ran it, or a reset's
// resume sequence took the nozzle to where it left it), the print waits for
// `resume`, and the resume's way back is the one the pause block has for the
// point where the print stopped, from where the printer stands.
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "gcode/serial/control/print_control.hpp"

namespace gcode::serial {

namespace {

// The printer stands where the first `taken` lines of `block` leave a
// stream at `at` (X, Y, Z and E).
bool ran_first(const std::vector<std::string>& block, std::size_t taken, const MachineState& at,
               const MachineState& printer) {
  MachineState s = at;
  for (std::size_t i = 0; i < taken; ++i) s.apply(Line::parse(block[i]));
  for (int a : {kX, kY, kZ, kE})
    if (s.known[static_cast<std::size_t>(a)] && std::abs(s.position[a] - printer.position[a]) > 1e-6) return false;
  return true;
}

}  // namespace

std::size_t PrintControl::resume_into_pause(const MachineState& at, const MachineState& parked, double retracted,
                                            double top_z, std::size_t taken) {
  PauseRecord& r = start_record("the journal's pause");
  const PausePoint point{at, retracted, top_z, &precision_};
  r.input_line = last_source_;
  r.block_number = sender_.last_submitted() + 1;
  r.block = true;
  handed_ = at;
  if (std::size_t sent = finish_block(point, parked, taken); sent > 0) return sent;
  PauseConfig c = pause_config(at);
  // Parked where it stands: the block's way back starts there.
  c.park = true;
  c.park_x = parked.position[kX];
  c.park_y = parked.position[kY];
  PauseBlock block = build_pause(point, c);
  MachineState block_end = at;
  for (const std::string& l : block.pause) track(l, block_end);
  stop_at(at, block_end, true);
  stop_.printer = parked;
  stop_.resume_lines = std::move(block.resume);
  diag_.info("the print was paused: waiting for resume");
  return 0;
}

// gc-send stopped inside the pause block: the block is made again as the
// print made it and its lines after the `taken` that ran go out, when those
// leave the head where the printer stands (else the pause options differ
// from the print's, and the head waits where it is).
std::size_t PrintControl::finish_block(const PausePoint& point, const MachineState& parked, std::size_t taken) {
  PauseConfig c = pause_config(point.state);
  PauseBlock block;
  try {
    config_.park.place_or_lift(printed_, precision_, c);
    block = build_pause(point, c);
  } catch (const std::exception& e) {
    // Half a block ran and the rest cannot be made: the head may stand half-way.
    if (taken > 0)
      diag_.warn(0, fmt::format("the journal's pause: the printer took {} lines of the pause block, which the pause "
                                "options given now cannot make again ({}); it waits where it stands",
                                taken, e.what()));
    return 0;
  }
  if (taken >= block.pause.size()) return 0;
  if (!ran_first(block.pause, taken, point.state, parked)) {
    diag_.warn(0, fmt::format("the journal's pause: the printer took {} lines of the pause block, which the pause "
                              "options given now do not make; it waits where it stands",
                              taken));
    return 0;
  }
  std::vector<std::string> rest(block.pause.begin() + static_cast<std::ptrdiff_t>(taken), block.pause.end());
  MachineState block_end = parked;
  for (const std::string& l : rest) track(l, block_end);
  stop_at(point.state, block_end, true);
  stop_.resume_lines = std::move(block.resume);
  submit_lines(rest, layer_);
  diag_.info(fmt::format("the print was pausing: the rest of the pause block ({} of {} lines) sent; waiting for resume",
                         rest.size(), block.pause.size()));
  return rest.size();
}

}  // namespace gcode::serial
