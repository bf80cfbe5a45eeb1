// make_vase_stl: writes the test meshes' wavy vase (tests/support/mesh/mesh_maker.hpp: a radius
// that waves with height and angle, open top) as a binary STL, at any size:
//
//   make_vase_stl HEIGHT_MM RINGS AROUND OUT.stl      (2 x RINGS x AROUND triangles and a floor)
//
// bench/parts/mesh-vase.sh times gc-shape vase --mesh and CuraEngine on it (60 1000 500: a
// million triangles).
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "mesh_maker.hpp"

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: make_vase_stl HEIGHT_MM RINGS AROUND OUT.stl\n");
    return 2;
  }
  const meshtest::TestMesh mesh = meshtest::wavy_vase(std::atof(argv[1]), std::atoi(argv[2]), std::atoi(argv[3]));
  std::ofstream out(argv[4], std::ios::binary);
  out << meshtest::binary_stl(mesh);
  if (!out) {
    std::fprintf(stderr, "make_vase_stl: cannot write %s\n", argv[4]);
    return 1;
  }
  std::printf("%zu\n", mesh.triangles.size());
  return 0;
}
