#pragma once
// gc-pause-at's options: where the pauses go (--before-layer, --after-layer,
// --z, --every, --layer-marker, --dry-run) and the pause itself
// (pause_options.hpp), mapped to transform/pause_stage.hpp's PauseTriggers.
#include <string>

#include "gcode/cli/pause_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/pause_stage.hpp"

namespace gcode::cli {

struct PauseAtOptions {
  FilterOptions io;
  std::string before_layer, after_layer, heights;
  int every = 0;
  bool dry_run = false;
  PauseOptions pause;
  PauseTriggers where;  // settled from the text above once parsed
};

// Every option, and the check that settles `where` (a usage error: no
// place given, layers counted from the end, a --z that is not numbers) and
// the pause (resolve_pause_options).
void add_pause_at_options(Tool& tool, PauseAtOptions& options);

}  // namespace gcode::cli
