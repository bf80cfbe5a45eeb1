// procedural/stl_reader.hpp: binary told from ASCII by size (a binary
// header may begin with "solid"), corners welded, normals ignored, and
// every malformed file refused with where it went wrong.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/procedural/stl_reader.hpp"
#include "mesh/mesh_maker.hpp"

namespace test_stl_reader {

using gcode::procedural::Mesh;
using gcode::procedural::MeshError;
using gcode::procedural::read_stl;

std::string refusal(const std::string& bytes) {
  try {
    read_stl(bytes, "m.stl");
  } catch (const MeshError& e) {
    return e.what();
  }
  return "";
}


TEST_CASE("stl_reader: a binary file whose header begins with solid, welded", "[shape][mesh]") {
  const meshtest::TestMesh cyl = meshtest::cylinder(15, 12, 48);
  const std::string bytes = meshtest::binary_stl(cyl);
  REQUIRE(bytes.rfind("solid", 0) == 0);
  const Mesh m = read_stl(bytes, "m.stl");
  CHECK(m.triangles.size() == cyl.triangles.size());
  CHECK(m.vertices.size() == 2 * 48 + 2);  // two rings and the two caps' centres
  const gcode::Box3 b = m.bounds();
  CHECK(b.max[2] == Approx(12));
  CHECK(b.max[0] == Approx(15).margin(1e-5));
}

TEST_CASE("stl_reader: a sloppy ASCII export welds to the same mesh", "[shape][mesh]") {
  const meshtest::TestMesh vase = meshtest::wavy_vase();
  const Mesh clean = read_stl(meshtest::binary_stl(vase), "m.stl");
  const Mesh sloppy = read_stl(meshtest::sloppy_ascii_stl(vase), "m.stl");
  CHECK(sloppy.vertices.size() == clean.vertices.size());
  CHECK(sloppy.triangles.size() == clean.triangles.size());
}

TEST_CASE("stl_reader: truncated, NaN, empty, broken words: refused with where", "[shape][mesh][errors]") {
  std::string cut = meshtest::binary_stl(meshtest::cylinder());
  cut.resize(cut.size() - 1);
  CHECK(refusal(cut).find("counting 192 triangles has 9684 bytes, this one 9683 (truncated") != std::string::npos);
  std::string more = meshtest::binary_stl(meshtest::cylinder());
  more[80] = static_cast<char>(more[80] + 1);  // the count says one triangle more than the file holds
  CHECK(refusal(more).find("counting 193 triangles") != std::string::npos);
  std::string inf = meshtest::binary_stl(meshtest::cylinder());
  for (int i = 0; i < 4; ++i) inf[84 + 12 + 4 + i] = "\x00\x00\x80\x7f"[i];  // +infinity as the first Y
  CHECK(refusal(inf) == "m.stl: triangle 1: a corner is not a finite number");
  CHECK(refusal("solid empty\nendsolid empty\n") == "m.stl: no triangles (an empty mesh)");
  CHECK(refusal("") == "m.stl: not an STL file (0 bytes)");
  CHECK(refusal("solid x\nfacet normal 0 0 1\nouter loop\nvertex 1 2 3\nvertex 1 2 3\nvertex 1 2 3\nendloop\nendfacet\n") ==
        "m.stl: line 9: the file ends inside the solid (no 'endsolid')");
  CHECK(refusal("solid x\nfacet normal 0 0 1\n outer loop\n vertex 1 2 inf\n").find("line 4: expected a number, not 'inf'") !=
        std::string::npos);
  CHECK(refusal("solid x\nfacet normal 0 0 1\n outer lop\n") == "m.stl: line 3: expected 'loop', not 'lop'");
  // Three corners that weld into one: the triangle is dropped, and with it the mesh.
  CHECK(refusal("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 0 0.0001\nvertex 0 0.0001 0\n"
                "endloop\nendfacet\nendsolid x\n") == "m.stl: no triangles (an empty mesh)");
}

}  // namespace test_stl_reader
