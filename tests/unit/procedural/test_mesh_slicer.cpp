// procedural/mesh_slicer.hpp and wall_outline.hpp: sections as closed
// counter-clockwise loops on the surface, a corner on the plane counted
// once, holes and islands found, the lean of a band.
#include <catch2/catch.hpp>

#include <cmath>

#include "gcode/procedural/mesh_slicer.hpp"
#include "gcode/procedural/outline_offset.hpp"
#include "gcode/procedural/stl_reader.hpp"
#include "gcode/procedural/wall_outline.hpp"
#include "mesh/mesh_maker.hpp"

namespace test_mesh_slicer {

using gcode::procedural::loop_area;
using gcode::procedural::Mesh;
using gcode::procedural::MeshSection;
using gcode::procedural::MeshSlicer;
using gcode::procedural::read_stl;
using gcode::procedural::wall_outline;
using gcode::procedural::WallOutline;

Mesh mesh_of(const meshtest::TestMesh& m) { return read_stl(meshtest::binary_stl(m), "m.stl"); }


TEST_CASE("mesh_slicer: a cylinder's section is its polygon, at any height, a corner height too", "[shape][mesh]") {
  const Mesh mesh = mesh_of(meshtest::twisted_prism(12, 15, 60, 30));
  MeshSlicer slicer(mesh);
  for (double z : {0.2, 0.5, 7.3, 7.5, 14.9}) {  // 0.5, 7.5: on a ring of corners, where the section is the square
    INFO(z);
    slicer.band(z, z);
    const MeshSection s = slicer.section(z);
    REQUIRE(s.loops.size() == 1);
    CHECK(s.open_ends == 0);
    const double area = loop_area(s.loops[0]);
    if (std::fmod(z, 0.5) == 0) {
      CHECK(s.loops[0].size() == 4);
      CHECK(area == Approx(24.0 * 24.0).epsilon(1e-6));
    } else {
      CHECK(s.loops[0].size() == 8);  // each side's two triangles cut
      CHECK(area > 560);
      CHECK(area < 576);
    }
  }
}

TEST_CASE("mesh_slicer: a mesh below and above z = 0, swept upwards: every section whole", "[shape][mesh]") {
  // Triangles sorted by the bits of their lowest Z: negative heights, -0 and +0 in their places.
  meshtest::TestMesh prism = meshtest::twisted_prism(12, 15, 60, 30);
  for (meshtest::Tri& t : prism.triangles)
    for (meshtest::P3& p : t) p.z -= 7.5;
  const Mesh mesh = mesh_of(prism);
  MeshSlicer slicer(mesh);
  for (double z = -7.4; z < 7.5; z += 0.25) {
    INFO(z);
    slicer.band(z, z);
    const MeshSection s = slicer.section(z);
    REQUIRE(s.loops.size() == 1);
    CHECK(s.open_ends == 0);
    CHECK(loop_area(s.loops[0]) > 560);
  }
}

TEST_CASE("mesh_slicer: a hole in the mesh, two islands, the lean of a band", "[shape][mesh]") {
  meshtest::TestMesh holed = meshtest::cylinder(10, 6, 32);
  holed.triangles.erase(holed.triangles.begin());
  const Mesh open = mesh_of(holed);
  MeshSlicer a(open);
  a.band(3, 3);
  CHECK(a.section(3).open_ends == 2);
  CHECK(wall_outline(a.section(3), 0.5, 0.01).problem == "the section does not close (the mesh has a hole there)");

  meshtest::TestMesh twins = meshtest::cylinder(8, 6, 32), other = twins;
  for (meshtest::Tri& t : other.triangles)
    for (meshtest::P3& p : t) p.x += 30;
  twins.triangles.insert(twins.triangles.end(), other.triangles.begin(), other.triangles.end());
  const Mesh two = mesh_of(twins);
  MeshSlicer b(two);
  b.band(3, 3);
  CHECK(b.section(3).loops.size() == 2);
  CHECK(wall_outline(b.section(3), 0.5, 0.01).problem == "the section splits into 2 islands (a vase has one wall)");
  CHECK(b.band_lean() == Approx(0).margin(1e-6));  // vertical walls; the lids are left out

  const Mesh shade = mesh_of(meshtest::sphere_shade());
  MeshSlicer c(shade);
  c.band(0.1, 0.4);
  CHECK(c.band_lean() == Approx(std::tan(50 * 3.14159265 / 180)).epsilon(0.05));  // the sphere at 140 degrees
}

}  // namespace test_mesh_slicer
