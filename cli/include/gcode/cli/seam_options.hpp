#pragma once
// The options of a splice's seam (seam.hpp), the same in every tool that
// joins G-code: --lift, --retract, --retract-speed, --travel-speed, --z-speed.
#include "gcode/cli/tool.hpp"
#include "gcode/transform/seam.hpp"

namespace gcode::cli {

void add_seam_options(Tool& tool, SeamOptions& options);

}  // namespace gcode::cli
