#pragma once
// A vase's wall as one rising spiral on a mesh (gc-shape vase --mesh).
//
// Turn k starts at z = base + k x pitch; at the fraction f of its length the
// nozzle is at base + (k + f) x pitch, on the bead line (wall_outline.hpp)
// of the section at that height less half a pitch, the middle of its bead.
// f is measured along the bead line from the point nearest where the last
// turn ended, so there is no seam: every turn continues the last, and a
// point lies one pitch above the point of the turn under it.
//
// The section is taken at the point's own height, to within the tolerance:
// a turn is cut into M pieces, each on the section at its middle, M enough
// that the steepest wall of the turn's band (MeshSlicer::band_lean) moves
// the surface at most the tolerance over half a piece's rise
// (lean x pitch / 2M). A vertical wall needs one section a turn; a
// leaning or twisted one more, at most kMaxPieces.
#include <vector>

#include "gcode/core/geometry.hpp"
#include "gcode/procedural/mesh_slicer.hpp"
#include "gcode/procedural/shape.hpp"
#include "gcode/procedural/wall_outline.hpp"

namespace gcode::procedural {

inline constexpr int kMaxPieces = 64;

struct SpiralWallOptions {
  double base = 0;    // mm, the Z the wall stands on (the bottom's top)
  double pitch = 0;   // mm a turn
  int turns = 0;
  double line_width = 0;
  double tolerance = 0;
  double model_top = 0;  // mm, sections are taken below it
};

// Appends one layer a turn to `out`, starting near `from` (the bottom's last
// point); heights it cannot print go to `problems`.
void spiral_wall(MeshSlicer& slicer, const SpiralWallOptions& options, Point2 from, std::vector<ShapeLayer>& out,
                 HeightProblems& problems);

// The section height for a nozzle height: kept just inside the model, where
// the ramp's first bead middles lie below the floor of a bottomless shade.
double section_height(double z, double model_top);

}  // namespace gcode::procedural
