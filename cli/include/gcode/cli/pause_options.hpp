#pragma once
// The options of a pause block (pause_sequence.hpp) and its park position
// (pause_context.hpp), the same in every tool that pauses a print: gc-pause-at
// writes the block into a file, gc-send sends it when asked. Groups "Printer"
// (--bed, --max-z, --park, --min-park-z) and "Pause" (--retract, --lift,
// --standby-temp, ... and, where the printer itself waits, --method/--dwell).
#include <string>

#include "gcode/cli/tool.hpp"
#include "gcode/core/print_area.hpp"
#include "gcode/transform/pause_context.hpp"
#include "gcode/transform/pause_sequence.hpp"

namespace gcode::cli {

struct PauseOptions {
  PauseConfig config;
  std::string bed, park, method = "M0", before, after, custom;
  double max_z = 0, standby = 0;
  bool no_heat_wait = false;
  bool standby_given = false, dwell_given = false, retract_given = false;
  bool with_method = true;  // --method and --dwell offered
};

// Adds both groups; without `with_method` the caller waits itself
// (PauseMethod::None) and --method/--dwell are not offered.
void add_pause_options(Tool& tool, PauseOptions& options, bool with_method);
// Checks the combinations once parsed (throws UsageError) and settles the
// config: method, standby, heat wait.
void resolve_pause_options(PauseOptions& options);
// Reads --before/--after (and a custom method's text) from files or text.
void load_pause_texts(PauseOptions& options);
// The park rules: the file's own bed and height (`area`: the slicer's
// environment first, then the file), then the options; the slicer's
// retraction where --retract was not given.
// Throws InputError when --min-park-z is above the printer.
ParkRules park_rules(const PauseOptions& options, const PrintArea& area, PauseConfig& config);

}  // namespace gcode::cli
