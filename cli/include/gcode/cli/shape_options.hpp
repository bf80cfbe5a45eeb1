#pragma once
// gc-shape's options and what they map to (procedural/shape.hpp's
// ShapeOptions, procedural/shape_gcode.hpp's ShapeGcodeOptions): the shape
// and its size (a vase: its mesh), the bead, and the program around it (temperatures, fan,
// start and end code, travel and retraction).
#include <string>

#include "gcode/cli/tool.hpp"
#include "gcode/procedural/shape_gcode.hpp"

namespace gcode::cli {

struct ShapeToolOptions {
  FilterOptions io;
  procedural::ShapeOptions shape;
  procedural::ShapeGcodeOptions gcode;
  std::string kind, center, start, end;  // SHAPE, --center X,Y, --start FILE, --end FILE
  std::string mesh, bed;                 // --mesh MODEL.stl, --bed WxDxH
};

// Every option, and the check that settles the kind and the centre
// (ShapeOptions::validate, ShapeGcodeOptions::validate: a usage error).
void add_shape_options(Tool& tool, ShapeToolOptions& options);

}  // namespace gcode::cli
