#pragma once
// gc-deform's options and what they map to (transform/deform_map.hpp's
// DeformFormulas, transform/deform.hpp's DeformOptions): the map (--xyz or
// --cylinder and its --center), the bead's factors, the tolerance, the caps
// and the bed. Formulas that muparser cannot read are a usage error, with
// the position, before anything is read.
#include <string>
#include <vector>

#include "gcode/cli/tool.hpp"
#include "gcode/transform/deform.hpp"
#include "gcode/transform/deform_map.hpp"

namespace gcode::cli {

struct DeformToolOptions {
  FilterOptions io;
  DeformFormulas formulas;
  DeformOptions deform;
  std::vector<std::string> xyz, cylinder;
  std::string center, bed;
  double filament_diameter = 0;  // 0: the file's, else 1.75
  bool keep_section = false;
};

// Every option, and the check that settles formulas, centre and bed.
void add_deform_options(Tool& tool, DeformToolOptions& options);

}  // namespace gcode::cli
