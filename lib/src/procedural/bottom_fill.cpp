#include "gcode/procedural/bottom_fill.hpp"

#include <algorithm>
#include <cmath>

#include "gcode/procedural/outline_offset.hpp"
#include "gcode/procedural/spiral_wall.hpp"

namespace gcode::procedural {

namespace {

constexpr double kJoinSteps = 2;  // a loop farther than this many line widths is reached by travel

std::size_t nearest_corner(const Polygon& loop, const Point2& p) {
  std::size_t best = 0;
  double d = 1e300;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const double di = distance_squared(loop[i], p);
    if (di < d) d = di, best = i;
  }
  return best;
}

// One layer's loops, from the corner of each nearest the last point.
void lay_loops(const std::vector<Polygon>& loops, double z, double bead, double line_width, bool first_layer,
               ShapeLayer& layer, Point2& at) {
  bool first = true;
  for (const Polygon& loop : loops) {
    const std::size_t start = nearest_corner(loop, at);
    const Point2& s = loop[start];
    const bool travel = (first && !first_layer) || distance(s, at) > kJoinSteps * line_width;
    layer.points.push_back({s.x, s.y, z, bead, travel});
    for (std::size_t i = 1; i <= loop.size(); ++i) {
      const Point2& p = loop[(start + i) % loop.size()];
      layer.points.push_back({p.x, p.y, z, bead, false});
    }
    at = s;
    first = false;
  }
}

}  // namespace

// Loop k is the outline moved in by k line widths, not loop k - 1 moved in by one: the same curve
// (moving in by a, then by b, is moving in by a + b: round joins take away discs, and the disc of
// a + b is the sum of the two), but nothing piles up: offset from the loop before, each loop would
// take the last one's arcs as corners, and Clipper's round join puts at least two points at every
// concave corner (on a wavy vase loops of 290 points grow to 3500, Clipper on them a third of a run).
// Arcs within an eighth of the tolerance: where the arcs of two corners meet far in, the corner
// between them lies up to twice that inside (a quarter of the tolerance, as the wall's simplification).
std::vector<Polygon> fill_loops(const Polygon& outline, double line_width, double tolerance) {
  std::vector<Polygon> loops{outline};
  for (int k = 1;; ++k) {
    std::vector<Polygon> ring = offset_inward(outline, k * line_width, tolerance / 8);
    if (ring.empty()) return loops;
    for (Polygon& piece : ring) loops.push_back(std::move(piece));
  }
}

void bottom_fill(MeshSlicer& slicer, const BottomFillOptions& o, std::vector<ShapeLayer>& out,
                 HeightProblems& problems) {
  Point2 at{1e300, 1e300};
  for (int i = 1; i <= o.layers; ++i) {
    const double z = i * o.layer_height;
    const double cut = section_height(z - o.layer_height / 2, o.model_top);
    slicer.band(cut, cut);
    ShapeLayer layer;
    layer.bottom = true;
    const WallOutline outline = wall_outline(slicer.section(cut), o.line_width, o.tolerance);
    if (!outline.problem.empty()) {
      problems.add(outline.problem, cut);
      out.push_back(std::move(layer));
      continue;
    }
    std::vector<Polygon> loops = fill_loops(outline.line, o.line_width, o.tolerance);
    if ((o.layers - i) % 2 == 0) std::reverse(loops.begin(), loops.end());  // outward: the last ends outside
    if (i == 1) at = loops.front()[0];
    lay_loops(loops, z, o.layer_height, o.line_width, i == 1, layer, at);
    out.push_back(std::move(layer));
  }
}

}  // namespace gcode::procedural
