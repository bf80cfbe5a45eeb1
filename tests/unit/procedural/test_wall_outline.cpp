// procedural/wall_outline.hpp: the bead line half a line width inside the
// outer loop (a hole inside it left out), and the problems by kind with
// their heights in one message.
#include <catch2/catch.hpp>

#include <cmath>

#include "gcode/procedural/wall_outline.hpp"

namespace test_wall_outline {

using gcode::Polygon;
using gcode::procedural::HeightProblems;
using gcode::procedural::MeshSection;
using gcode::procedural::wall_outline;

Polygon square(double half, double cx = 0) {
  return {{cx - half, -half}, {cx + half, -half}, {cx + half, half}, {cx - half, half}};
}

TEST_CASE("wall_outline: half a line width inside the outer loop, a hole left out", "[shape][mesh]") {
  MeshSection s;
  s.loops = {square(5, 0), square(3, 0)};  // a thick wall: the outer face and the inner
  const auto w = wall_outline(s, 0.5, 0.01);
  REQUIRE(w.problem.empty());
  for (const gcode::Point2& p : w.line) CHECK(std::max(std::fabs(p.x), std::fabs(p.y)) == Approx(4.75).margin(1e-4));
}

TEST_CASE("wall_outline: islands, holes, a section thinner than the bead", "[shape][mesh][errors]") {
  MeshSection two;
  two.loops = {square(5, 0), square(5, 20)};
  CHECK(wall_outline(two, 0.5, 0.01).problem == "the section splits into 2 islands (a vase has one wall)");
  MeshSection open = two;
  open.open_ends = 2;
  CHECK(wall_outline(open, 0.5, 0.01).problem == "the section does not close (the mesh has a hole there)");
  MeshSection thin;
  thin.loops = {{{0, 0}, {10, 0}, {10, 0.3}, {0, 0.3}}};
  CHECK(wall_outline(thin, 0.5, 0.01).problem == "the section is narrower than a line width");
  MeshSection none;
  CHECK(wall_outline(none, 0.5, 0.01).problem == "the mesh has no section");
  MeshSection neck;  // two squares joined by a strip 0.3 mm wide
  neck.loops = {{{0, 0}, {5, 0}, {5, 2.35}, {8, 2.35}, {8, 0}, {13, 0}, {13, 5}, {8, 5}, {8, 2.65}, {5, 2.65}, {5, 5}, {0, 5}}};
  CHECK(wall_outline(neck, 0.5, 0.01).problem ==
        "the bead's line splits into 2 pieces (a neck narrower than a line width)");
}

TEST_CASE("wall_outline: problems by kind, with the range of heights", "[shape][mesh]") {
  HeightProblems p;
  CHECK(p.empty());
  p.add("islands", 1.5);
  p.add("islands", 1.8);
  p.add("a hole", 2.25);
  p.add("islands", 3);
  CHECK(p.message() == "islands at z = 1.5 .. 3 mm (3 heights); a hole at z = 2.25 mm");
}

}  // namespace test_wall_outline
