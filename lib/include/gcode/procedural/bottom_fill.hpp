#pragma once
// A vase's filled bottom: `layers` flat layers at z = layer height x i, each
// filled inside the section at the middle of its bead with concentric loops
// one line width apart, the outermost on the wall's bead line
// (wall_outline.hpp). Loops are joined by a bead where the next is one step
// in; pieces that a concave outline splits off are reached by a travel, as
// is each layer's start. The layers alternate inward and outward so that
// the last ends on its outermost loop, where the wall's ramp begins.
#include <vector>

#include "gcode/procedural/mesh_slicer.hpp"
#include "gcode/procedural/shape.hpp"
#include "gcode/procedural/wall_outline.hpp"

namespace gcode::procedural {

struct BottomFillOptions {
  int layers = 0;
  double layer_height = 0;
  double line_width = 0;
  double tolerance = 0;
  double model_top = 0;
};

// Appends one layer each to `out`; the first layer's first point is where
// the path starts, every later layer's first is reached by a travel. Heights it cannot fill go to `problems`.
void bottom_fill(MeshSlicer& slicer, const BottomFillOptions& options, std::vector<ShapeLayer>& out,
                 HeightProblems& problems);

// The loops that fill `outline`, outermost first: `outline`, then ring by
// ring the pieces of `outline` moved in by 1, 2, ... line widths.
std::vector<Polygon> fill_loops(const Polygon& outline, double line_width, double tolerance);

}  // namespace gcode::procedural
