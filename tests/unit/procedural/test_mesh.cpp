// procedural/mesh.hpp: corners welded within the merge distance (across
// the cells of its grid too), collapsed triangles dropped, the placement.
#include <catch2/catch.hpp>

#include "gcode/procedural/mesh.hpp"

namespace test_mesh {

using gcode::procedural::Mesh;
using gcode::procedural::MeshBuilder;

TEST_CASE("mesh: corners within the merge distance are one vertex, across grid cells too", "[shape][mesh]") {
  MeshBuilder b(0.001);
  b.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  b.add_triangle({1.0004, 0, 0}, {0, 0.9996, 0}, {1, 1, 0});  // 0.9996 and 1.0004: neighbouring cells
  b.add_triangle({0, 0, 0}, {0.0002, 0, 0}, {0, 0.0002, 0});   // collapses to a point
  const Mesh m = b.take();
  CHECK(m.vertices.size() == 4);
  REQUIRE(m.triangles.size() == 2);
  CHECK(m.triangles[1][0] == m.triangles[0][1]);
  CHECK(m.triangles[1][1] == m.triangles[0][2]);
}

TEST_CASE("mesh: many vertices (the grid grows), then placed on the bed about a centre", "[shape][mesh]") {
  MeshBuilder b(0.001);
  for (int i = 0; i < 5000; ++i) b.add_triangle({i * 0.01, 0, 5}, {i * 0.01, 1, 5}, {i * 0.01, 0, 7});
  Mesh m = b.take();
  CHECK(m.vertices.size() == 15000);
  m.place(2, 100, 50);
  const gcode::Box3 box = m.bounds();
  CHECK(box.min[2] == 0);
  CHECK(box.max[2] == Approx(4));
  CHECK((box.min[0] + box.max[0]) / 2 == Approx(100));
  CHECK((box.min[1] + box.max[1]) / 2 == Approx(50));
  CHECK(box.max[0] - box.min[0] == Approx(2 * 49.99));
}

}  // namespace test_mesh
