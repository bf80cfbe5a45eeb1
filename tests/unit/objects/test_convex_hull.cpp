// The convex hull (objects/convex_hull.hpp): inner and repeated points
// left out, counter-clockwise from the lowest-leftmost point; the builder
// folds batches without losing a point of the hull.
#include <catch2/catch.hpp>

#include "gcode/objects/convex_hull.hpp"

TEST_CASE("convex hull: a square with points inside and on its edges is its four corners", "[convex_hull]") {
  const gcode::Polygon hull =
      gcode::convex_hull({{1, 1}, {0, 0}, {2, 0}, {1, 0}, {2, 2}, {0, 2}, {0, 0}, {1, 2}, {0.5, 1.5}});
  REQUIRE(hull.size() == 4);
  CHECK((hull[0].x == 0 && hull[0].y == 0));
  CHECK((hull[1].x == 2 && hull[1].y == 0));
  CHECK((hull[2].x == 2 && hull[2].y == 2));
  CHECK((hull[3].x == 0 && hull[3].y == 2));
  CHECK(gcode::convex_hull({{1, 1}, {1, 1}}).size() == 1);
}

TEST_CASE("convex hull: the builder's hull of many batches is the hull of all points", "[convex_hull]") {
  gcode::HullBuilder b;
  // A circle of 10000 points, r 5 around (100, 50), then points inside.
  for (int i = 0; i < 10000; ++i) {
    const double a = 2 * 3.141592653589793 * i / 10000;
    b.add(100 + 5 * std::cos(a), 50 + 5 * std::sin(a));
  }
  for (int i = 0; i < 10000; ++i) b.add(100 + (i % 7) * 0.1, 50 + (i % 5) * 0.1);
  const gcode::Polygon hull = b.hull();
  CHECK(hull.size() > 1000);
  for (const gcode::Point2& p : hull) CHECK(std::hypot(p.x - 100, p.y - 50) == Approx(5).margin(1e-9));
}
