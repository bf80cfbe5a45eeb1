#pragma once
// Outlines moved inward and thinned out, for a bead that must lie inside a
// section, with round joins, so that at a concave corner the bead's edge
// follows the arc at exactly half a line width from the corner. A loop whose
// offset stays simple is drawn directly (the common case, and far cheaper);
// otherwise Clipper (Debian's libpolyclipping) resolves it, so that parts
// narrower than the offset vanish or split off instead of folding over.
#include <vector>

#include "gcode/core/geometry.hpp"

namespace gcode::procedural {

// `loop` (counter-clockwise, closed, first point not repeated) moved inward
// by `distance` mm; arcs within `arc_tolerance`. The pieces it falls into,
// each counter-clockwise; none when nothing is left.
std::vector<Polygon> offset_inward(const Polygon& loop, double distance, double arc_tolerance);

// The fewest points of `loop` that keep every dropped point within
// `tolerance` of the new loop (Douglas-Peucker, closed). A fine mesh cut at
// a height gives many points on a straight or gently curved wall.
Polygon simplify_loop(const Polygon& loop, double tolerance);

double loop_area(const Polygon& loop);  // signed: above 0 counter-clockwise

}  // namespace gcode::procedural
