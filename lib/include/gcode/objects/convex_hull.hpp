#pragma once
// The convex hull of points in XY: an object's outline on the plate (what
// Klipper's EXCLUDE_OBJECT_DEFINE POLYGON= and gc-objects --svg draw).
//
// HullBuilder takes any number of points in bounded memory: it keeps the
// hull so far and a batch of new points, and folds the batch in when full.
#include <vector>

#include "gcode/core/geometry.hpp"

namespace gcode {

// Counter-clockwise, the lowest-leftmost point first, no point repeated;
// fewer than three points for degenerate input.
Polygon convex_hull(std::vector<Point2> points);

class HullBuilder {
 public:
  void add(double x, double y) {
    pending_.push_back({x, y});
    if (pending_.size() >= kBatch) fold();
  }
  // The hull of everything added.
  Polygon hull() {
    fold();
    return hull_;
  }

 private:
  static constexpr std::size_t kBatch = 4096;
  void fold();
  Polygon hull_;
  std::vector<Point2> pending_;
};

}  // namespace gcode
