// transform/deform_map.hpp: points through the formulas in both frames, the
// cross-section factor (dFZ/dz x FC), errors naming the option.
#include <catch2/catch.hpp>

#include <cmath>

#include "gcode/transform/deform_map.hpp"

using gcode::DeformFormulas;
using gcode::DeformFrame;
using gcode::DeformMap;
using gcode::Point3;

namespace {

// (GCC 12 warns wrongly, -Wrestrict, on a short literal assigned to a member string here.)
DeformFormulas with_width(DeformFormulas f, std::string width) {
  f.width = std::move(width);
  return f;
}

}  // namespace

TEST_CASE("cylinder frame: the identity and the dish", "[deform]") {
  DeformFormulas f;
  f.frame = DeformFrame::Cylindrical;
  f.map = {"r", "theta", "z"};
  f.center_x = 110, f.center_y = 100;
  DeformMap same(f);
  const Point3 p = same.apply({125, 90, 3});
  CHECK(p.x == Approx(125));
  CHECK(p.y == Approx(90));
  CHECK(p.z == 3);
  CHECK(same.section({125, 90, 3}) == Approx(1));
  CHECK_FALSE(same.identity());  // only --xyz x y z is known to be one by its text

  f.map = {"r + 1.05*z", "theta", "0.3*z"};
  DeformMap dish(f);
  const Point3 q = dish.apply({140, 100, 10});  // r = 30
  CHECK(q.x == Approx(110 + 40.5));
  CHECK(q.y == Approx(100));
  CHECK(q.z == Approx(3));
  CHECK(dish.section({140, 100, 10}) == Approx(0.3));
  f.layer_scale = false;
  CHECK(DeformMap(with_width(f, "2")).section({140, 100, 10}) == Approx(2));
}

TEST_CASE("xyz frame with layer and s, speed", "[deform]") {
  DeformFormulas f;
  f.map = {"x + layer", "y + s", "z*z"};
  f.speed = "1 + x/100";
  DeformMap m(f);
  m.set_context(3, 7.5);
  const Point3 p = m.apply({1, 2, 3});
  CHECK(p.x == 4);
  CHECK(p.y == 9.5);
  CHECK(p.z == 9);
  CHECK(m.section({1, 2, 3}) == Approx(6));  // d(z^2)/dz
  CHECK(m.speed({50, 0, 0}) == Approx(1.5));
  f.map = {"x", "y", "z"};
  f.speed.clear();
  CHECK(DeformMap(f).identity());
}

TEST_CASE("a bad formula names the option, the formula and where", "[deform][errors]") {
  DeformFormulas f;
  f.frame = DeformFrame::Cylindrical;
  f.map = {"r", "theta + x", "z"};
  try {
    DeformMap m(f);
    FAIL("accepted");
  } catch (const gcode::ExpressionError& e) {
    const std::string what = e.what();
    CHECK(what.find("--cylinder FTHETA 'theta + x'") == 0);
    CHECK(e.position == 9);
  }
  f.map = {"r", "theta", "z"};
  CHECK_THROWS_WITH(DeformMap(with_width(f, "2 *")), Catch::StartsWith("--width FC '2 *'"));
}
