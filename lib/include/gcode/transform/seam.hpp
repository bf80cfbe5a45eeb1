#pragma once
// The seam between two pieces of G-code: the lines that take the printer
// from where one stream left it to where the next block expects it, so that
// the printer cannot tell the block came from elsewhere.
//
// Both sides are a StreamPoint (stream_tracker.hpp): the machine state (modes, position, E
// coordinate, F, tool), the filament the stream retracted and has not pushed
// back, the carried settings (temperatures, fans, flow, pressure advance)
// and, on the printed side, the highest Z printed so far. The seam:
//
//   1. absolute positioning for its own moves (G90; Marlin's G90 also makes
//      E absolute, so a relative-E stream gets its M83 back at once);
//   2. retract if nothing is retracted (G10 where the stream uses firmware
//      retraction), so the travel does not string;
//   3. lift above everything printed so far (and above both sides' Z);
//   4. the tool and the settings that differ (heaters first, waited for when
//      they rise), while the nozzle is clear of the part;
//   5. travel in XY to where the block starts, down to its layer's Z;
//   6. unretract to the block's own retraction state;
//   7. the block's positioning mode, E mode (unless the caller converts the
//      block's E to the printed side's mode), E coordinate (G92 E) and F.
//
// The filament the seam pushes in total is exactly what was retracted on the
// printed side minus what the block expects retracted: retract and unretract
// are the same amount when both sides are in the same retraction state.
// Every number is an exact decimal (fixed.hpp): positions the block is at are
// written back exactly, heights the seam makes up at the input's precision.
#include <string>
#include <vector>

#include "gcode/core/line_builder.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/transform/stream_tracker.hpp"

namespace gcode {

struct SeamOptions {
  double lift = 1;            // mm above the highest Z printed for the travel
  double retract = 1;         // mm retracted for the travel when nothing is (0: never)
  double retract_speed = 35;  // mm/s, also for the unretract
  double travel_speed = 50;   // mm/s in XY
  double z_speed = 10;        // mm/s for the lift and the way down
  double max_z = 0;           // the printer's height limit; 0 = unknown

  // Throws std::invalid_argument naming the option that is out of range.
  void validate() const;
};

struct Seam {
  std::vector<std::string> lines;
  double safe_z = 0;          // the height of the travel
  double net_filament = 0;    // what the seam's E moves push in total (mm)
  bool e_mode_differs = false;  // the block's E mode is not the printed side's (convert_e)
  bool relative_e = false;      // the E mode the printer is in after the seam
};

// The lines from `from` (the printed side) to `to` (the block side). With
// `convert_e` the printed side keeps its E mode and the caller rewrites the
// block's E words into it (a block from a file in the other mode); without,
// the seam ends in the block's mode. Throws std::invalid_argument when the
// printed side's head position is unknown or either side is in inches.
Seam build_seam(const StreamPoint& from, const StreamPoint& to, const SeamOptions& options,
                const Precision& precision, bool convert_e);

}  // namespace gcode
