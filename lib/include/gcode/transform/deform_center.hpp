#pragma once
// Where a cylindrical deformation turns by default: the centre of the box
// round the print's extrusions in its layers (the start code's purge line
// and the end code's park left out), from one reading of the input.
#include "gcode/core/geometry.hpp"
#include "gcode/core/layer_marker.hpp"

namespace gcode {

// Reads `fd` to its end; false when the layers extrude nothing. `e_relative`:
// 1 or 0 for a file that never sets the E mode, -1 to leave it to the file.
bool extrusion_centre(int fd, const LayerMarkers& markers, int e_relative, Point2& centre);

}  // namespace gcode
