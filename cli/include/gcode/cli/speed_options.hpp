#pragma once
// gc-speedup's options and what they map to (transform/speed.hpp's
// SpeedOptions): the change (--factor, --speed, --ramp), the region, what
// changes, the caps, the firmware route (--m220); then what the file must
// say (the ramp's layers, the filament for --max-flow, the firmware for
// --m220-restore auto), and the messages about the change.
#include <string>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/speed.hpp"

namespace gcode::cli {

struct SpeedToolOptions {
  FilterOptions io;
  SelectionText where;
  SpeedOptions speed;
  std::string ramp;                   // --ramp F1:F2
  std::string m220_restore = "auto";  // auto|backup|reset
  bool diameter_given = false;        // --filament-diameter was on the command line
};

// Every option with its checks (a usage error: no change, two changes, a
// bad ramp, --m220-restore without --m220, SpeedOptions::validate).
void add_speed_options(Tool& tool, SpeedToolOptions& options);

// What the input decides, before the run: the layers of a ramp (reads the
// input once), the filament diameter for --max-flow (the file's, else 1.75
// with a warning), the M220 restore for auto (m220_restore_for_flavor), and
// a warning when the firmware's whole percents round the factor.
void resolve_speed_from_input(SpeedToolOptions& options, Filter& run, const LayerSelection& where, Diagnostics& diag);

// After the run: the capped moves (a warning naming each cap), the moves left
// alone, and what was changed (information).
void report_speed_change(const SpeedOptions& options, const SpeedStats& stats, Diagnostics& diag);

}  // namespace gcode::cli
