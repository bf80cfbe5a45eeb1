#pragma once
// The section of a mesh at height z (background.md §4): every triangle that
// straddles the plane is cut along its two crossing edges, giving one
// segment; segments are joined into closed loops where they end on the same
// mesh edge (a hash of edges, so the duplicate points of neighbouring
// triangles are one point by construction, not by a distance).
//
// A corner exactly at the height counts as above it, so every triangle
// crosses the plane on exactly two edges or none, and neighbours always
// agree about their common edge.
//
// Speed: the triangles are sorted by their lowest corner once; heights are
// visited upwards through bands (band(lo, hi)), and a band keeps only the
// triangles that overlap it, so a section costs the triangles near its
// height, not the whole mesh.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gcode/core/geometry.hpp"
#include "gcode/procedural/mesh.hpp"

namespace gcode::procedural {

struct MeshSection {
  std::vector<Polygon> loops;  // closed (the first point is not repeated), counter-clockwise
  std::size_t open_ends = 0;   // segment ends with no neighbour: the mesh has a hole at this height
  std::size_t crowded_edges = 0;  // edges shared by more than two triangles (not a manifold)
};

class MeshSlicer {
 public:
  explicit MeshSlicer(const Mesh& mesh);

  // Keeps the triangles overlapping [lo, hi]. `lo` must not go down from one
  // call to the next (a sweep upwards).
  void band(double lo, double hi);
  // The section at z, which must lie in the current band.
  MeshSection section(double z) const;
  // The steepest lean of the band's walls: horizontal mm per mm of height
  // (0 for vertical walls); near-flat triangles (a floor, a lid) left out.
  double band_lean() const;

 private:
  const Mesh& mesh_;
  std::vector<std::uint32_t> by_bottom_;  // triangles by their lowest Z
  std::vector<double> bottom_, top_;      // each triangle's Z range
  std::size_t next_ = 0;                  // the first of by_bottom_ not yet taken into a band
  std::vector<std::uint32_t> active_;
  double lo_ = -1e300, hi_ = -1e300;
};

}  // namespace gcode::procedural
