// procedural/outline_offset.hpp: Clipper's inward offset (round at a
// concave corner, pieces where it splits), the closed Douglas-Peucker.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "gcode/procedural/outline_offset.hpp"
#include "mesh/loop_distance.hpp"

namespace test_outline_offset {

using gcode::Polygon;
using gcode::procedural::loop_area;
using gcode::procedural::offset_inward;
using gcode::procedural::simplify_loop;

TEST_CASE("outline_offset: an L moved inward: straight edges, an arc round the concave corner", "[shape][mesh]") {
  const Polygon l = {{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}};
  const auto pieces = offset_inward(l, 1, 0.005);
  REQUIRE(pieces.size() == 1);
  CHECK(loop_area(pieces[0]) > 0);
  // Every point 1 mm from the L's outline (round the concave corner (4, 4) too), within the arc tolerance.
  for (const gcode::Point2& p : pieces[0]) CHECK(meshtest::loop_distance(p, l) == Approx(1).margin(0.006));
  CHECK(offset_inward(l, 1.9, 0.005).size() == 1);  // arms 4 mm wide: 1.9 leaves a thin L
  CHECK(offset_inward(l, 5, 0.005).empty());
  CHECK(offset_inward({{0, 0}, {10, 0}, {10, 1}, {0, 1}}, 0.6, 0.005).empty());
}

TEST_CASE("outline_offset: a neck narrower than twice the offset splits the loop in two", "[shape][mesh]") {
  // Two 10 mm squares joined by a 1 mm wide, 5 mm long neck: moved 0.6 inward, the neck's two sides
  // cross without any edge turning back, so only the crossing test sends it to Clipper.
  const Polygon dumbbell = {{0, 0}, {10, 0}, {10, 4.5}, {15, 4.5}, {15, 0}, {25, 0},
                            {25, 10}, {15, 10}, {15, 5.5}, {10, 5.5}, {10, 10}, {0, 10}};
  const auto pieces = offset_inward(dumbbell, 0.6, 0.005);
  REQUIRE(pieces.size() == 2);
  // Each an 8.8 mm square, bulging a little into the neck's mouth round its two concave corners.
  for (const Polygon& p : pieces) CHECK(loop_area(p) == Approx(8.8 * 8.8 + 0.1).margin(0.1));
  CHECK(offset_inward(dumbbell, 0.4, 0.005).size() == 1);
}

TEST_CASE("outline_offset: simplify_loop keeps corners, drops points within the tolerance", "[shape][mesh]") {
  Polygon fine;
  for (int i = 0; i < 100; ++i) fine.push_back({i * 0.1, 0.0001 * (i % 2)});
  for (int i = 0; i < 100; ++i) fine.push_back({10, i * 0.1});
  fine.push_back({0, 10});
  const Polygon kept = simplify_loop(fine, 0.001);
  CHECK(kept.size() == 4);
  Polygon circle;
  for (int i = 0; i < 720; ++i) circle.push_back({10 * std::cos(i * M_PI / 360), 10 * std::sin(i * M_PI / 360)});
  const Polygon coarse = simplify_loop(circle, 0.01);
  CHECK(coarse.size() < 720);
  CHECK(coarse.size() > 40);  // a chord of 10 mm radius keeps 0.01 mm at 5.1 degrees: about 70
}

}  // namespace test_outline_offset
