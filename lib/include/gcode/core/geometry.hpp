#pragma once
// Points and boxes in the printer's coordinates (mm): the extent of a print,
// the bed, an outline to draw. One set of types for every piece.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace gcode {

struct Point2 {
  double x = 0, y = 0;
};

using Polygon = std::vector<Point2>;

// Squared, for comparisons (no square root; std::hypot, careful of overflow
// that millimetres never reach, costs ten times a multiplication).
inline double distance_squared(const Point2& a, const Point2& b) {
  return (b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y);
}
inline double distance(const Point2& a, const Point2& b) { return std::sqrt(distance_squared(a, b)); }

// An axis-aligned box in XY. Default-constructed it is empty: add() grows it.
struct Box2 {
  double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;

  bool empty() const { return min_x > max_x || min_y > max_y; }
  void add(double x, double y) {
    min_x = std::min(min_x, x);
    min_y = std::min(min_y, y);
    max_x = std::max(max_x, x);
    max_y = std::max(max_y, y);
  }
  void add(const Box2& b) {
    if (b.empty()) return;
    add(b.min_x, b.min_y);
    add(b.max_x, b.max_y);
  }
  bool contains(double x, double y) const { return x >= min_x && x <= max_x && y >= min_y && y <= max_y; }
  double width() const { return max_x - min_x; }
  double depth() const { return max_y - min_y; }
  Point2 centre() const { return {(min_x + max_x) / 2, (min_y + max_y) / 2}; }
  Polygon outline() const { return {{min_x, min_y}, {max_x, min_y}, {max_x, max_y}, {min_x, max_y}}; }
};

// The same in XYZ ([0] X, [1] Y, [2] Z).
struct Box3 {
  std::array<double, 3> min{1e300, 1e300, 1e300};
  std::array<double, 3> max{-1e300, -1e300, -1e300};

  bool empty() const { return min[0] > max[0]; }
  void add(double x, double y, double z) {
    const double p[3] = {x, y, z};
    for (std::size_t i = 0; i < 3; ++i) {
      min[i] = std::min(min[i], p[i]);
      max[i] = std::max(max[i], p[i]);
    }
  }
  Box2 xy() const { return empty() ? Box2{} : Box2{min[0], min[1], max[0], max[1]}; }
};

}  // namespace gcode
