#pragma once
// A triangle mesh as the slicer needs it (background.md §4): shared
// vertices, triangles as three vertex indices, so that two triangles with a
// common edge name it by the same two indices and their section segments
// join there exactly. Corners closer than a merge distance become one vertex
// (a sloppy export writes the same corner with noise); triangles that then
// collapse are dropped. The file's normals play no part: a section needs
// only the corners.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gcode/core/geometry.hpp"

namespace gcode::procedural {

// What a mesh cannot be used for, said for the user (the tool exits 1).
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;

  Box3 bounds() const;
  // Scales about the origin, then moves the mesh so that its lowest point
  // is at z = 0 and its XY box is centred on (center_x, center_y).
  void place(double scale, double center_x, double center_y);
};

// Builds a Mesh corner by corner, welding corners within `merge_distance`.
// A grid of cells kCellMerges merge distances wide finds the neighbours: a
// corner is looked up in its own cell first (where an exact copy is), then
// only in the neighbour cells whose border it is within the merge distance
// of (none for most corners, not the 26 around it). The grid is a flat hash
// of chains through the vertices (a slot per cell hash, a `next` per
// vertex).
class MeshBuilder {
 public:
  explicit MeshBuilder(double merge_distance);
  void reserve(std::size_t triangles);
  void add_triangle(const Vec3& a, const Vec3& b, const Vec3& c);
  Mesh take();

 private:
  using Cell = std::array<std::int64_t, 3>;
  std::uint32_t weld(const Vec3& p);
  bool find_in(const Cell& cell, const Vec3& p, std::uint32_t& index) const;
  std::size_t slot(const Cell& cell) const;
  void grow();

  static constexpr std::uint32_t kNone = ~0u;
  static constexpr double kCellMerges = 8;
  double merge_;
  double cell_;  // mm, a cell's width
  Mesh mesh_;
  std::vector<std::uint32_t> heads_;  // per slot, the last vertex whose cell hashes there
  std::vector<std::uint32_t> next_;   // per vertex, the one before it in its slot
  std::vector<Cell> cells_;           // per vertex, its cell
};

}  // namespace gcode::procedural
