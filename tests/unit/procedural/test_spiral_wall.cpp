// procedural/spiral_wall.hpp: one layer a turn, Z rising with the fraction
// of the turn, each turn starting where the last ended, on the bead line.
#include <catch2/catch.hpp>

#include <cmath>

#include "gcode/procedural/mesh_slicer.hpp"
#include "gcode/procedural/spiral_wall.hpp"
#include "gcode/procedural/stl_reader.hpp"
#include "mesh/mesh_maker.hpp"

namespace test_spiral_wall {

using namespace gcode::procedural;

TEST_CASE("spiral_wall: a cylinder's wall, a turn a layer, rising, seamless", "[shape][mesh]") {
  const gcode::procedural::Mesh mesh = read_stl(meshtest::binary_stl(meshtest::cylinder(15, 6, 180)), "m.stl");
  MeshSlicer slicer(mesh);
  std::vector<ShapeLayer> turns;
  HeightProblems problems;
  spiral_wall(slicer, {.base = 0, .pitch = 0.3, .turns = 20, .line_width = 0.5, .tolerance = 0.01, .model_top = 6},
              {15, 0}, turns, problems);
  CHECK(problems.empty());
  REQUIRE(turns.size() == 20);
  CHECK(turns[0].start_bead == 0);
  double z = 0;
  for (std::size_t k = 0; k < turns.size(); ++k) {
    REQUIRE(!turns[k].points.empty());
    for (const PathPoint& p : turns[k].points) {
      CHECK(p.z >= z);
      z = p.z;
      CHECK(std::hypot(p.x, p.y) <= 14.75 + 1e-9);
      CHECK(std::hypot(p.x, p.y) >= 15 * std::cos(M_PI / 180) - 0.25 - 1e-6);
      CHECK(p.bead == Approx(std::min(p.z, 0.3)));
    }
    CHECK(turns[k].points.back().z == Approx(0.3 * (k + 1)));
  }
  CHECK(z == 6);
}

TEST_CASE("spiral_wall: a section height stays inside the model", "[shape][mesh]") {
  CHECK(section_height(-0.15, 10) == Approx(1e-4));
  CHECK(section_height(5, 10) == 5);
  CHECK(section_height(10, 10) == Approx(10 - 1e-4));
}

}  // namespace test_spiral_wall
