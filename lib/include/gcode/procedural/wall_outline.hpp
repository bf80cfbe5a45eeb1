#pragma once
// Where a vase's bead runs at one height: the section's outer loop (a hole
// inside it, the inner face of a model with a thick wall, is not the vase's
// wall), thinned out within a quarter of the tolerance and moved inward by
// half a line width, so that the bead's outer face lies on the model's
// surface. What makes a height unprintable as one wall is said, not
// guessed around: islands (a vase has one wall), a section that does not
// close (a hole in the mesh), none at all, a bead line that splits (a neck
// narrower than a line width).
#include <string>
#include <vector>

#include "gcode/core/geometry.hpp"
#include "gcode/procedural/mesh_slicer.hpp"

namespace gcode::procedural {

struct WallOutline {
  Polygon line;         // the bead's centre line, counter-clockwise; empty when `problem` says why
  std::string problem;  // "" when the height is printable
};

WallOutline wall_outline(const MeshSection& section, double line_width, double tolerance);

// Problems by kind, with the heights they occur at, for one message at the
// end instead of one at the first height.
class HeightProblems {
 public:
  void add(const std::string& problem, double z);
  bool empty() const { return kinds_.empty(); }
  // "the section splits into 2 islands at z = 3.150 .. 8.850 mm (20 heights); ..."
  std::string message() const;

 private:
  struct Kind {
    std::string problem;
    double first = 0, last = 0;
    int count = 0;
  };
  std::vector<Kind> kinds_;
};

}  // namespace gcode::procedural
