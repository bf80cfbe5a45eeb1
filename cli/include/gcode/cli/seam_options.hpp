#pragma once
// The options of a splice's seam (seam.hpp), the same in every tool that
// joins G-code: --lift, --retract, --retract-speed, --travel-speed, --z-speed.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/layer_edits.hpp"
#include "gcode/transform/seam.hpp"

namespace gcode::cli {

void add_seam_options(Tool& tool, SeamOptions& options);

// The files a splice reads besides the input (gc-swap-layer's --with and
// --file, gc-relayer's new file), each opened, made seekable (a pipe is kept
// in a temp file) and indexed by layer once, however often it is named.
class SpliceFiles {
 public:
  // The files by name, in the order given. Throws UsageError for "" or "-"
  // (standard input is the print).
  std::vector<SpliceFile> open(const std::vector<std::string>& names, const LayerMarkers& markers);

 private:
  std::map<std::string, std::unique_ptr<InputFile>> files_;
  std::map<std::string, std::unique_ptr<LayerIndex>> indexes_;
};

// The printer a splice works on: the input's (Filter::print_area), with a
// warning for each of `others` sliced for another one (printer_difference),
// and its height as the ceiling of the seams' lift (`seam.max_z`; 0 unknown).
PrintArea splice_printer(Filter& run, const std::vector<SpliceFile>& others, SeamOptions& seam, Diagnostics& diag);

}  // namespace gcode::cli
