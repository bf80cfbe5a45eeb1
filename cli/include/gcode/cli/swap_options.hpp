#pragma once
// gc-swap-layer's options and what they map to (transform/layer_edits.hpp's
// LayerEditsText, the seam of seam_options.hpp): --layer/--with,
// --skip/--keep-z, --repeat, --insert-after/--file.
#include "gcode/cli/seam_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/layer_edits.hpp"

namespace gcode::cli {

struct SwapToolOptions {
  FilterOptions io;
  LayerEditsText edits;
  SeamOptions seam;
};

// Every option, the seam's among them, and their checks (LayerEditsText::validate, SeamOptions::validate).
void add_swap_options(Tool& tool, SwapToolOptions& options);

}  // namespace gcode::cli
