// procedural/mesh.hpp: corners welded within the merge distance (across
// the cells of its grid too), collapsed triangles dropped, the placement.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

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

TEST_CASE("mesh: copies jittered about the grid's cell borders weld to their corner, in every direction",
          "[shape][mesh]") {
  // Corners on the borders of the grid's cells (multiples of 0.008 mm for a 0.001 mm merge) and a
  // little either side; each written in several triangles, every copy moved up to 0.0005 mm per axis.
  const double merge = 0.001;
  std::vector<gcode::procedural::Vec3> corners;
  for (int i = 0; i < 125; ++i) {
    const double side[3] = {0.0006 * (i % 3 - 1), 0.0006 * (i / 3 % 3 - 1), 0.0006 * (i / 9 % 3 - 1)};
    corners.push_back({0.008 * (i % 5) + side[0], 0.008 * (i / 5 % 5) + side[1], 0.008 * (i / 25) + side[2]});
  }
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-merge / 2, merge / 2);
  auto copy = [&](std::size_t i) {
    const gcode::procedural::Vec3& c = corners[i % corners.size()];
    return gcode::procedural::Vec3{c.x + jitter(random), c.y + jitter(random), c.z + jitter(random)};
  };
  MeshBuilder b(merge);
  for (std::size_t i = 0; i < 4 * corners.size(); ++i) b.add_triangle(copy(i), copy(i + 1), copy(i + 2));
  const Mesh m = b.take();
  CHECK(m.vertices.size() == corners.size());
  REQUIRE(m.triangles.size() == 4 * corners.size());
  for (std::size_t i = 0; i < m.triangles.size(); ++i)  // corner i's copies are all the vertex of its first
    CHECK(m.triangles[i][0] == m.triangles[i % corners.size()][0]);
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
