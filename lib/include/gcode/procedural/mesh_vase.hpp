#pragma once
// gc-shape vase --mesh: a mesh's outer wall as one seamless spiral on a
// filled bottom, as a ShapePath that shape_gcode.hpp writes like any shape.
//
// The model stands on the bed (its lowest point at z = 0), scaled by
// ShapeOptions::scale, its XY box centred on the centre. The bottom is
// bottom_layers flat layers of layer_height (bottom_fill.hpp); the wall
// (spiral_wall.hpp) rises from there to the model's top, its pitch the
// layer height shortened so that whole turns reach the top exactly, the
// first turn ramping up from the bottom as the helix does from the bed.
// Refused with a MeshError that names the heights: a model wider, deeper
// or taller than the bed, one too low for the bottom and a turn, and every
// height whose section is not one closed wall (wall_outline.hpp).
#include <string_view>

#include "gcode/procedural/mesh.hpp"
#include "gcode/procedural/shape.hpp"

namespace gcode::procedural {

// `name` is the model's, for the header and the messages.
ShapePath mesh_vase(Mesh mesh, const ShapeOptions& options, std::string_view name);

}  // namespace gcode::procedural
