#include "gcode/serial/control/pause_reentry.hpp"

#include <cmath>
#include <cstddef>

#include <fmt/format.h>

#include "gcode/core/line.hpp"

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

PauseReentry::PauseReentry(const MachineState& at, double retracted, double top_z, const Precision* precision,
                           const MachineState& parked, std::size_t taken)
    : at_(at), retracted_(retracted), top_z_(top_z), precision_(precision), parked_(parked), taken_(taken) {}

bool PauseReentry::finish_block(const PauseConfig& config) {
  PauseBlock block = build_pause(point(), config);
  if (taken_ >= block.pause.size()) return false;
  if (!ran_first(block.pause, taken_, at_, parked_)) {
    warning_ = fmt::format("the printer took {} lines of the pause block, which the pause options given now do not "
                           "make; it waits where it stands",
                           taken_);
    return false;
  }
  block_lines_ = block.pause.size();
  rest_.assign(block.pause.begin() + static_cast<std::ptrdiff_t>(taken_), block.pause.end());
  resume_from_ = parked_;
  for (const std::string& l : rest_) resume_from_.apply(Line::parse(l));
  resume_lines_ = std::move(block.resume);
  return true;
}

void PauseReentry::cannot_make(std::string_view why) {
  // Half a block ran and the rest cannot be made: the head may stand half-way.
  if (taken_ > 0)
    warning_ = fmt::format("the printer took {} lines of the pause block, which the pause options given now cannot "
                           "make again ({}); it waits where it stands",
                           taken_, why);
}

void PauseReentry::park_here(PauseConfig config) {
  // Parked where it stands: the block's way back starts there.
  config.park = true;
  config.park_x = parked_.position[kX];
  config.park_y = parked_.position[kY];
  PauseBlock block = build_pause(point(), config);
  rest_.clear();
  resume_from_ = at_;
  for (const std::string& l : block.pause) resume_from_.apply(Line::parse(l));
  resume_lines_ = std::move(block.resume);
}

}  // namespace gcode::serial
