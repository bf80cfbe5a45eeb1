#pragma once
// gc-layers' options: the table (--json, --where, --density), the cut
// (--extract, --z-range), the time (--time, --profile) and the pictures
// (--svg, --svg-sheet), with the rules for combining them.
#include <string>

#include "gcode/cli/tool.hpp"

namespace gcode::cli {

struct LayersToolOptions {
  FilterOptions io;
  bool json = false;
  std::string extract;
  std::string z_range;
  int where = 0;
  double density = 1.24;
  double filament_diameter = 0;  // 0: the slicer's (environment or file), else 1.75
  // --time, --svg, --svg-sheet
  bool time = false;
  std::string profile;
  bool no_heat_time = false;
  bool time_by_feature = false;  // implies time
  std::string svg;
  std::string svg_sheet;
  std::string svg_out;
  bool no_travel = false;
  double svg_size = 800;

  bool cutting() const { return !extract.empty() || !z_range.empty(); }
  bool pictures() const { return !svg.empty() || !svg_sheet.empty(); }
};


// Every option, and the checks of their combinations (usage errors: -o or -i
// without a cut, pictures with a cut, a range that does not parse).
void add_layers_options(Tool& tool, LayersToolOptions& options);

}  // namespace gcode::cli
