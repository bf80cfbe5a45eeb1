#include "gcode/procedural/mesh.hpp"

#include <cmath>

namespace gcode::procedural {

Box3 Mesh::bounds() const {
  Box3 b;
  for (const Vec3& v : vertices) b.add(v.x, v.y, v.z);
  return b;
}

void Mesh::place(double scale, double center_x, double center_y) {
  for (Vec3& v : vertices) v = {v.x * scale, v.y * scale, v.z * scale};
  const Box3 b = bounds();
  if (b.empty()) return;
  const double dx = center_x - (b.min[0] + b.max[0]) / 2, dy = center_y - (b.min[1] + b.max[1]) / 2;
  for (Vec3& v : vertices) v = {v.x + dx, v.y + dy, v.z - b.min[2]};
}

std::size_t MeshBuilder::CellHash::operator()(const Cell& c) const noexcept {
  const auto mix = [](std::uint64_t h, std::int64_t v) {
    return (h ^ static_cast<std::uint64_t>(v)) * 0x9E3779B97F4A7C15ull;
  };
  return static_cast<std::size_t>(mix(mix(mix(0, c[0]), c[1]), c[2]) >> 7);
}

MeshBuilder::MeshBuilder(double merge_distance) : merge_(merge_distance) {}

void MeshBuilder::reserve(std::size_t triangles) {
  mesh_.triangles.reserve(triangles);
  mesh_.vertices.reserve(triangles / 2 + 3);
  grid_.reserve(triangles / 2 + 3);
}

bool MeshBuilder::find_in(const Cell& cell, const Vec3& p, std::uint32_t& index) const {
  const auto [from, to] = grid_.equal_range(cell);
  for (auto it = from; it != to; ++it) {
    const Vec3& q = mesh_.vertices[it->second];
    if (std::fabs(q.x - p.x) <= merge_ && std::fabs(q.y - p.y) <= merge_ && std::fabs(q.z - p.z) <= merge_) {
      index = it->second;
      return true;
    }
  }
  return false;
}

std::uint32_t MeshBuilder::weld(const Vec3& p) {
  const Cell cell = {static_cast<std::int64_t>(std::floor(p.x / merge_)),
                     static_cast<std::int64_t>(std::floor(p.y / merge_)),
                     static_cast<std::int64_t>(std::floor(p.z / merge_))};
  std::uint32_t index = 0;
  if (find_in(cell, p, index)) return index;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz)
        if ((dx != 0 || dy != 0 || dz != 0) && find_in({cell[0] + dx, cell[1] + dy, cell[2] + dz}, p, index))
          return index;
  index = static_cast<std::uint32_t>(mesh_.vertices.size());
  mesh_.vertices.push_back(p);
  grid_.emplace(cell, index);
  return index;
}

void MeshBuilder::add_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const std::array<std::uint32_t, 3> t = {weld(a), weld(b), weld(c)};
  // Welding may collapse a sliver to an edge or a point: it has no section.
  if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) mesh_.triangles.push_back(t);
}

Mesh MeshBuilder::take() {
  grid_.clear();
  return std::move(mesh_);
}

}  // namespace gcode::procedural
