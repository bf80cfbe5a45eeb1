// procedural/shape.hpp: the primitives' points lie on their curves, a whole
// number of turns reaches the height, the first turn ramps from the bed, and
// chords keep to the tolerance.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "gcode/procedural/shape.hpp"

using gcode::procedural::PathPoint;
using gcode::procedural::ShapeKind;
using gcode::procedural::ShapeLayer;
using gcode::procedural::ShapeOptions;
using gcode::procedural::ShapePath;

namespace {

ShapeOptions options(ShapeKind kind) {
  ShapeOptions o;
  o.kind = kind;
  o.diameter = 40;
  o.height = 6;
  return o;
}

// Largest distance of a chord's midpoint from the circle of radius r.
double worst_midpoint(const ShapePath& path, double r) {
  ShapeLayer layer;
  PathPoint at = path.start();
  double worst = 0;
  for (int i = 0; i < path.layer_count(); ++i) {
    path.layer(i, layer);
    for (const PathPoint& p : layer.points) {
      const double mx = (at.x + p.x) / 2 - path.options().center_x, my = (at.y + p.y) / 2 - path.options().center_y;
      worst = std::max(worst, std::fabs(std::hypot(mx, my) - r));
      at = p;
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("shape names parse both ways, and nothing else does", "[shape]") {
  for (const char* n : {"circle", "spiral", "helix", "cylinder", "polygon", "cone"}) {
    ShapeKind k{};
    REQUIRE(gcode::procedural::parse_shape_kind(n, k));
    CHECK(gcode::procedural::shape_kind_name(k) == n);
  }
  ShapeKind k{};
  CHECK_FALSE(gcode::procedural::parse_shape_kind("Helix", k));
  CHECK_FALSE(gcode::procedural::parse_shape_kind("", k));
}

TEST_CASE("a helix: whole turns reach the height, one layer a turn, the first ramps up from the bed", "[shape]") {
  const ShapePath path(options(ShapeKind::Helix));
  CHECK(path.turns() == 20);  // 6 / 0.3
  CHECK(path.layer_count() == 20);
  CHECK(path.pitch() == Approx(0.3));
  CHECK(path.start().z == 0);
  ShapeLayer layer;
  path.layer(0, layer);
  CHECK(layer.points.back().z == Approx(0.3));
  CHECK(layer.points.back().bead == Approx(0.3));
  CHECK(layer.points[layer.points.size() / 2].bead == Approx(layer.points[layer.points.size() / 2].z));
  path.layer(19, layer);
  CHECK(layer.points.back().z == Approx(6));
  CHECK(layer.points.back().x == Approx(130));  // a whole turn: back above the start
  for (const PathPoint& p : layer.points) CHECK(p.bead == Approx(0.3));

  ShapeOptions odd = options(ShapeKind::Helix);
  odd.height = 6.1;
  const ShapePath shortened(odd);
  CHECK(shortened.turns() == 21);
  CHECK(shortened.pitch() == Approx(6.1 / 21));
  CHECK(shortened.top() == Approx(6.1));
}

TEST_CASE("chords keep to the tolerance, with room for the rounding of written coordinates", "[shape]") {
  for (double tol : {0.002, 0.01, 0.1}) {
    ShapeOptions o = options(ShapeKind::Helix);
    o.tolerance = tol;
    const ShapePath path(o);
    const double worst = worst_midpoint(path, 20);
    CHECK(worst <= tol - o.rounding + 1e-12);
    CHECK(worst > (tol - o.rounding) * 0.5);  // not far more points than needed
  }
  const ShapePath circle(options(ShapeKind::Circle));
  CHECK(circle.layer_count() == 1);
  CHECK(worst_midpoint(circle, 20) <= 0.01);
}

TEST_CASE("a cone's radius follows the height, a polygon has its corners, a spiral one line width per turn",
          "[shape]") {
  ShapeLayer layer;
  const ShapePath cone(options(ShapeKind::Cone));
  cone.layer(cone.layer_count() - 1, layer);
  CHECK(std::hypot(layer.points.back().x - 110, layer.points.back().y - 110) == Approx(15));
  cone.layer(0, layer);
  CHECK(std::hypot(layer.points.front().x - 110, layer.points.front().y - 110) == Approx(20).margin(0.02));

  ShapeOptions hex = options(ShapeKind::Polygon);
  const ShapePath polygon(hex);
  polygon.layer(3, layer);
  REQUIRE(layer.points.size() == 6);
  for (int j = 0; j < 6; ++j) {
    const double a = 2 * std::numbers::pi * (j + 1) / 6;
    CHECK(layer.points[static_cast<std::size_t>(j)].x == Approx(110 + 20 * std::cos(a)));
    CHECK(layer.points[static_cast<std::size_t>(j)].y == Approx(110 + 20 * std::sin(a)).margin(1e-9));
  }

  const ShapePath spiral(options(ShapeKind::Spiral));
  spiral.layer(0, layer);
  const PathPoint end = layer.points.back();
  CHECK(std::hypot(end.x - 110, end.y - 110) == Approx(1.0));  // four line widths across
  CHECK(end.z == Approx(0.3));
  // 19 mm of radius at 0.5 mm a turn: 38 turns.
  double turned = 0;
  PathPoint at = spiral.start();
  for (const PathPoint& p : layer.points) {
    double d = std::atan2(p.y - 110, p.x - 110) - std::atan2(at.y - 110, at.x - 110);
    if (d < -std::numbers::pi) d += 2 * std::numbers::pi;
    if (d > std::numbers::pi) d -= 2 * std::numbers::pi;
    turned += d;
    at = p;
  }
  CHECK(turned / (2 * std::numbers::pi) == Approx(38));
}

TEST_CASE("a cylinder: a bottom spiral out to the wall, the wall from where it ends, on top of it", "[shape]") {
  const ShapePath path(options(ShapeKind::Cylinder));
  CHECK(path.layer_count() == 1 + 19);
  ShapeLayer bottom, wall;
  path.layer(0, bottom);
  path.layer(1, wall);
  CHECK(bottom.bottom);
  CHECK_FALSE(wall.bottom);
  const PathPoint edge = bottom.points.back();
  CHECK(std::hypot(edge.x - 110, edge.y - 110) == Approx(20));
  CHECK(edge.z == Approx(0.3));
  // The wall's first point is a small step on from the bottom's last, barely above it.
  CHECK(std::hypot(wall.points.front().x - edge.x, wall.points.front().y - edge.y) < 1.5);
  CHECK(wall.points.front().bead < 0.01);
  CHECK(wall.points.back().z == Approx(0.6));
  CHECK(path.top() == Approx(6));
}

TEST_CASE("shape options that make no sense are refused, naming the option", "[shape]") {
  auto refused = [](ShapeOptions o, const char* option) {
    try {
      o.validate();
      FAIL("accepted");
    } catch (const std::invalid_argument& e) {
      CHECK(std::string(e.what()).find(option) != std::string::npos);
    }
  };
  ShapeOptions o = options(ShapeKind::Helix);
  o.height = 0.1;
  refused(o, "--height");
  o = options(ShapeKind::Polygon);
  o.sides = 2;
  refused(o, "--sides");
  o = options(ShapeKind::Helix);
  o.tolerance = 0.001;
  refused(o, "--tolerance");
  o = options(ShapeKind::Spiral);
  o.inner_diameter = 50;
  refused(o, "--inner-diameter");
  o = options(ShapeKind::Helix);
  o.diameter = std::nan("");
  refused(o, "--diameter");
}
