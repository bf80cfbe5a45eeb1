#pragma once
// A print that gc-send --resume finds paused in its journal goes back into
// the pause: the block is not sent again (the printer ran it, or a reset's
// resume sequence took the nozzle to where it left it), the print waits for
// `resume`, and the resume's way back is the one the pause block has for the
// point where the print stopped, from where the printer stands.
//
// When gc-send stopped inside the block, the block is made again as the
// print made it and its lines after the `taken` that ran go out, when those
// leave the head where the printer stands (else the pause options differ
// from the print's, and the head waits where it is).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/machine_state.hpp"
#include "gcode/transform/pause_sequence.hpp"

namespace gcode::serial {

class PauseReentry {
 public:
  // The print stopped at `at` (with `retracted` mm of its own retraction
  // pending and `top_z` printed; `precision`: the input's decimals);
  // `parked`: where the printer stands (the journal's state after the block
  // and anything typed); `taken`: the lines of the pause block that ran.
  PauseReentry(const MachineState& at, double retracted, double top_z, const Precision* precision,
               const MachineState& parked, std::size_t taken);

  // The block made again with `config` (the options given now, placed as
  // the print placed them; build_pause may throw): true when the rest of it
  // is to go out (rest()). False: the head waits where it stands (park_here).
  bool finish_block(const PauseConfig& config);
  // The options given now cannot make the block again (`why`).
  void cannot_make(std::string_view why);
  // Parked where the printer stands: the way back of the block `config`
  // makes, from there.
  void park_here(PauseConfig config);

  const std::vector<std::string>& rest() const { return rest_; }
  std::size_t block_lines() const { return block_lines_; }
  // Where the block (or its rest) leaves the stream: the resume's start.
  const MachineState& resume_from() const { return resume_from_; }
  std::vector<std::string>& resume_lines() { return resume_lines_; }
  // Why the rest of a block half run cannot go out ("": nothing to say).
  const std::string& warning() const { return warning_; }

 private:
  PausePoint point() const { return PausePoint{at_, retracted_, top_z_, precision_}; }

  MachineState at_;
  double retracted_;
  double top_z_;
  const Precision* precision_;
  MachineState parked_;
  std::size_t taken_;
  std::vector<std::string> rest_;
  std::size_t block_lines_ = 0;
  MachineState resume_from_;
  std::vector<std::string> resume_lines_;
  std::string warning_;
};

}  // namespace gcode::serial
