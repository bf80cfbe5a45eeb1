#pragma once
// The distance of a point from a closed loop's edges, by brute force (tests
// of the offsets measure their output with it, sharing no code with them).
#include <algorithm>
#include <cmath>

#include "gcode/core/geometry.hpp"

namespace meshtest {

inline double loop_distance(const gcode::Point2& p, const gcode::Polygon& loop) {
  double d = 1e300;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const gcode::Point2& a = loop[i];
    const gcode::Point2& b = loop[(i + 1) % loop.size()];
    const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / l2, 0.0, 1.0) : 0;
    d = std::min(d, std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy));
  }
  return d;
}

}  // namespace meshtest
