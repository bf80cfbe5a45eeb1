#pragma once
// A ShapePath as complete, printable G-code (gc-shape).
//
// E follows the bead exactly: a piece from point a to point b lays a bead of
// line width x the mean of the two bead heights (the ramp of a first turn
// changes linearly along it) over its length as written, so its filament is
// width x height x length / filament area. E is relative (M83), written with
// 5 decimals and its rounding carried from piece to piece, so the total is
// exact. X, Y and Z have 3 decimals, F none.
//
// The text reads like Cura's, so every gc tool reads it: ";FLAVOR:Marlin",
// ";LAYER_COUNT:n", ";LAYER:n" (0-based) at the start of every turn (one turn
// is one layer: gc-layers counts turns), ";TYPE:WALL-OUTER" (";TYPE:SKIN" for
// flat fills), ";MINX:" .. ";MAXZ:" (the print's box, which gc-deform takes
// its centre from), and a header listing every parameter. A rising spiral
// has no layer-change move and no retraction: each turn continues the last.
// Start and end code are gc-litho's built-in Marlin ones (start_end_code.hpp)
// unless the caller passes its own text; the travel from the purge line to
// the path's start (retract, lift, over, down, unretract) ends the start code.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/procedural/shape.hpp"

namespace gcode::procedural {

struct ShapeGcodeOptions {
  double speed = 40;              // mm/s, printing
  double travel_speed = 150;      // mm/s
  double filament_diameter = 1.75;
  double nozzle_temp = 210;       // C
  double bed_temp = 60;           // C
  double retract_length = 1;      // mm, before the travel to the start (0 = none)
  double retract_speed = 35;      // mm/s
  int fan = 255;                  // M106 S.. from the second layer; 0 = off
  std::string start_code;         // instead of the built-in start ("" = built-in)
  std::string end_code;
  std::string start_name;         // where they came from, for the header
  std::string end_name;
  // Throws std::invalid_argument naming the option that makes no sense.
  void validate() const;
};

struct ShapeGcodeStats {
  int layers = 0;
  double filament = 0;  // mm, in the layers (the purge line not counted)
  double length = 0;    // mm of extruded path
  std::size_t moves = 0;
};

using ShapeTextOut = std::function<void(std::string_view)>;

// The header's "name = value" lines, in order.
std::vector<std::string> shape_parameters(const ShapePath& path, const ShapeGcodeOptions& options);

// Writes the program to `out`: the header and start code, then one chunk a
// layer, then the end code. Throws std::invalid_argument for bad options.
ShapeGcodeStats write_shape_gcode(const ShapePath& path, const ShapeGcodeOptions& options, const ShapeTextOut& out);

}  // namespace gcode::procedural
