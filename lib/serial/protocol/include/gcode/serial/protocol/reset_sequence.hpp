#pragma once
// The lines that bring a printer that reset mid-print back to the print
// (issue 22, §2): everything it knew is gone (position, homing, heaters,
// modes, line numbers), but the part still stands on the bed and the nozzle
// just above it, where the last move that ran left it.
//
//   1. the bed, then the hot end, back to their targets, waited for
//      (M190, M109): the part must stay stuck, and nothing may extrude cold;
//   2. Z declared where the nozzle stands (G92 Z: it cannot be homed over the
//      part) and the nozzle lifted off the part; only then X and Y homed
//      (G28 X Y, never Z), so neither the heating nor the homing happens
//      with the nozzle on the part (gc-relayer --resume-from-z does the same);
//   3. Transition::between from there: above everything printed, over to
//      the target, down, a prime as after a retraction, then the target's
//      modes, E (G92 E), F, fan and M220/M221 factors.
//
// A delta homes all its towers at once, Z with them: it cannot come back
// this way (xy_homing_refusal says what to do instead).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "gcode/core/line_builder.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/transform/transition.hpp"

namespace gcode::serial {

// What a resume after a reset needs of the print up to a command, besides
// its machine state: kept by the sender for every command and by the
// journal in its records (top, retr, prime).
struct ResumeTrack {
  double top_z = 0;       // the highest Z extruded at
  double retracted = 0;   // mm retracted and not pushed back
  double retraction = 0;  // the longest retraction so far (a firmware one's too): what a resume primes
  // A command that pushed `filament` mm (negative: retracted), moving the
  // head or not, and left the nozzle at `z`. `own`: a line of gc-send's
  // own (a pause's unload is no retraction of the print's to prime).
  void step(double filament, bool moves_head, double z, bool own) {
    if (filament > 0 && moves_head) {
      top_z = std::max(top_z, z);
      retracted = 0;
    } else if (filament < 0) {
      retracted -= filament;
      if (!own) retraction = std::max(retraction, retracted);
    } else if (filament > 0) {
      retracted = std::max(0.0, retracted - filament);
    }
  }
};

struct ResetResume {
  MachineState target;     // the machine after the last command that surely ran
  double top_z = 0;        // the highest Z extruded at so far (the part's top)
  // Where the nozzle stands (it stopped somewhere between the target and
  // the newest move the printer took); NaN: at the target's Z.
  double nozzle_z = std::numeric_limits<double>::quiet_NaN();
  double retracted = 0;    // mm the print had retracted at the target and not pushed back
  double prime = 0;        // mm pushed back before going on (the print's retraction length)
};

// Throws std::invalid_argument when the way cannot be known (inches, a
// target whose position was never known: resume from the start instead).
std::vector<std::string> reset_resume_lines(const ResetResume& how, const Precision& precision,
                                            const TransitionMoves& moves = {});

// Why a printer that cannot home X and Y alone is not resumed, and the
// gc-relayer --resume-from-z recipe that finishes the part instead.
// `z`: the height it stopped at; `input`: the file printed ("-": a stream).
std::string xy_homing_refusal(double z, const std::string& input);

}  // namespace gcode::serial
