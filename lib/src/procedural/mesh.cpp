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

MeshBuilder::MeshBuilder(double merge_distance)
    : merge_(merge_distance), cell_(std::fmax(merge_distance * kCellMerges, 1e-9)), heads_(1024, kNone) {}

void MeshBuilder::reserve(std::size_t triangles) {
  mesh_.triangles.reserve(triangles);
  mesh_.vertices.reserve(triangles / 2 + 3);
  next_.reserve(triangles / 2 + 3);
  cells_.reserve(triangles / 2 + 3);
  std::size_t slots = 1024;
  while (slots < triangles) slots *= 2;  // about twice the vertices: short chains
  heads_.assign(slots, kNone);
}

std::size_t MeshBuilder::slot(const Cell& c) const {
  std::uint64_t h = 0;
  for (const std::int64_t v : c) h = (h ^ static_cast<std::uint64_t>(v)) * 0x9E3779B97F4A7C15ull;
  return static_cast<std::size_t>(h >> 29) & (heads_.size() - 1);
}

void MeshBuilder::grow() {
  heads_.assign(heads_.size() * 2, kNone);
  for (std::uint32_t v = 0; v < cells_.size(); ++v) {
    const std::size_t s = slot(cells_[v]);
    next_[v] = heads_[s];
    heads_[s] = v;
  }
}

bool MeshBuilder::find_in(const Cell& cell, const Vec3& p, std::uint32_t& index) const {
  for (std::uint32_t v = heads_[slot(cell)]; v != kNone; v = next_[v]) {
    const Vec3& q = mesh_.vertices[v];
    if (cells_[v] == cell && std::fabs(q.x - p.x) <= merge_ && std::fabs(q.y - p.y) <= merge_ &&
        std::fabs(q.z - p.z) <= merge_) {
      index = v;
      return true;
    }
  }
  return false;
}

std::uint32_t MeshBuilder::weld(const Vec3& p) {
  // A neighbour cell can hold a corner within the merge distance only if p is that close to the
  // border between them (cells are kCellMerges merge distances wide; the reach a little more, for rounding).
  constexpr double kReach = 1.001 / kCellMerges;
  const double at[3] = {p.x / cell_, p.y / cell_, p.z / cell_};
  Cell cell{};
  int from[3], to[3];
  for (int k = 0; k < 3; ++k) {
    const double f = std::floor(at[k]);
    cell[k] = static_cast<std::int64_t>(f);
    from[k] = at[k] - f <= kReach ? -1 : 0;
    to[k] = at[k] - f >= 1 - kReach ? 1 : 0;
  }
  std::uint32_t index = 0;
  if (find_in(cell, p, index)) return index;
  for (int dx = from[0]; dx <= to[0]; ++dx)
    for (int dy = from[1]; dy <= to[1]; ++dy)
      for (int dz = from[2]; dz <= to[2]; ++dz)
        if ((dx != 0 || dy != 0 || dz != 0) && find_in({cell[0] + dx, cell[1] + dy, cell[2] + dz}, p, index))
          return index;
  index = static_cast<std::uint32_t>(mesh_.vertices.size());
  mesh_.vertices.push_back(p);
  cells_.push_back(cell);
  const std::size_t s = slot(cell);
  next_.push_back(heads_[s]);
  heads_[s] = index;
  if (cells_.size() > heads_.size() / 2) grow();
  return index;
}

void MeshBuilder::add_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const std::array<std::uint32_t, 3> t = {weld(a), weld(b), weld(c)};
  // Welding may collapse a sliver to an edge or a point: it has no section.
  if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) mesh_.triangles.push_back(t);
}

Mesh MeshBuilder::take() {
  heads_.clear();
  next_.clear();
  cells_.clear();
  return std::move(mesh_);
}

}  // namespace gcode::procedural
