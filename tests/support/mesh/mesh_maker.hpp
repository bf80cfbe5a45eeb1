#pragma once
// Test meshes for gc-shape vase --mesh, made here and written as STL files
// of their own (no library code: the library's reader is what they test).
//
//   cylinder       a faceted cylinder, closed top and bottom
//   wavy_vase      a vase whose radius waves with height and angle, open top
//   twisted_prism  a square prism turned 60 degrees over its height: sharp
//                  corners on leaning, twisting faces
//   star           a concave five-pointed star, extruded
//   sphere_shade   a band of a sphere, open at both ends (a lamp shade)
// Every one is centred on the Z axis and stands on z = 0.
#include <array>
#include <string>
#include <vector>

namespace meshtest {

struct P3 {
  double x = 0, y = 0, z = 0;
};
using Tri = std::array<P3, 3>;  // counter-clockwise seen from outside

struct TestMesh {
  std::string name;
  std::vector<Tri> triangles;
  double height = 0;
};

TestMesh cylinder(double radius = 15, double height = 12, int facets = 48);
TestMesh wavy_vase(double height = 20, int rings = 40, int around = 96);
TestMesh twisted_prism(double half_side = 12, double height = 15, double twist_degrees = 60, int rings = 30);
TestMesh star(double outer = 18, double inner = 8, double height = 10, int points = 5);
TestMesh sphere_shade(double radius = 16, double from_degrees = 40, double to_degrees = 140, int rings = 40,
                      int around = 96);

// Binary STL whose 80-byte header begins with "solid" (as many exporters
// write it), normals written as the triangle's.
std::string binary_stl(const TestMesh& mesh);
// ASCII STL as a careless exporter writes it: normals flipped, and every
// corner written with noise of up to `jitter` mm, so that the copies of one
// vertex in its triangles differ.
std::string sloppy_ascii_stl(const TestMesh& mesh, double jitter = 1e-5);

}  // namespace meshtest
