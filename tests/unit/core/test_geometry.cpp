// Points and boxes (core/geometry.hpp): an empty box grows by add(), an
// empty box added changes nothing, edges are inside.
#include <catch2/catch.hpp>

#include "gcode/core/geometry.hpp"

using gcode::Box2;
using gcode::Box3;

TEST_CASE("geometry: a default box is empty and grows with each point", "[geometry]") {
  Box2 b;
  CHECK(b.empty());
  CHECK_FALSE(b.contains(0, 0));
  b.add(10, 20);
  CHECK_FALSE(b.empty());  // one point is a box of no size
  CHECK(b.width() == 0);
  CHECK(b.contains(10, 20));
  b.add(-5, 40);
  b.add(3, 25);
  CHECK(b.min_x == -5);
  CHECK(b.max_x == 10);
  CHECK(b.min_y == 20);
  CHECK(b.max_y == 40);
  CHECK(b.width() == 15);
  CHECK(b.depth() == 20);
  CHECK(b.centre().x == 2.5);
  CHECK(b.centre().y == 30);
}

TEST_CASE("geometry: contains includes the edges", "[geometry]") {
  Box2 b{0, 0, 100, 50};
  CHECK(b.contains(0, 0));
  CHECK(b.contains(100, 50));
  CHECK(b.contains(100, 0));
  CHECK_FALSE(b.contains(100.0001, 25));
  CHECK_FALSE(b.contains(50, -0.0001));
}

TEST_CASE("geometry: adding an empty box changes nothing", "[geometry]") {
  Box2 b{1, 2, 3, 4};
  b.add(Box2{});
  CHECK(b.min_x == 1);
  CHECK(b.max_y == 4);
  Box2 e;
  e.add(Box2{});
  CHECK(e.empty());
  e.add(b);
  CHECK(e.min_x == 1);
  CHECK(e.min_y == 2);
  CHECK(e.max_x == 3);
  CHECK(e.max_y == 4);
}

TEST_CASE("geometry: the outline runs round the box", "[geometry]") {
  auto o = Box2{0, 0, 2, 1}.outline();
  REQUIRE(o.size() == 4);
  CHECK((o[0].x == 0 && o[0].y == 0));
  CHECK((o[1].x == 2 && o[1].y == 0));
  CHECK((o[2].x == 2 && o[2].y == 1));
  CHECK((o[3].x == 0 && o[3].y == 1));
}

TEST_CASE("geometry: Box3 and its XY shadow", "[geometry]") {
  Box3 b;
  CHECK(b.empty());
  CHECK(b.xy().empty());
  b.add(1, 2, 0.2);
  b.add(-1, 5, 3);
  CHECK_FALSE(b.empty());
  CHECK(b.min[2] == 0.2);
  CHECK(b.max[2] == 3);
  Box2 xy = b.xy();
  CHECK(xy.min_x == -1);
  CHECK(xy.max_x == 1);
  CHECK(xy.min_y == 2);
  CHECK(xy.max_y == 5);
}
