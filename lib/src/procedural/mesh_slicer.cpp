#include "gcode/procedural/mesh_slicer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace gcode::procedural {

namespace {

constexpr double kSamePoint = 1e-9;  // mm: a corner on the plane gives its point twice
constexpr double kFlat = 10;         // lean beyond which a triangle is a floor or a lid, not a wall

// One end of a segment, on the mesh edge it crosses.
struct SegmentEnd {
  std::uint64_t edge;
  std::uint32_t end;  // segment * 2 + which end
};

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
}

double signed_area(const Polygon& p) {
  double a = 0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += p[j].x * p[i].y - p[i].x * p[j].y;
  return a / 2;
}

// The loops through the segments' ends, joined where two ends share an edge.
void join(const std::vector<Point2>& points, std::vector<SegmentEnd>& ends, MeshSection& out) {
  std::sort(ends.begin(), ends.end(), [](const SegmentEnd& a, const SegmentEnd& b) { return a.edge < b.edge; });
  constexpr std::uint32_t kNone = ~0u;
  std::vector<std::uint32_t> partner(points.size(), kNone);
  for (std::size_t i = 0; i < ends.size();) {
    std::size_t j = i;
    while (j < ends.size() && ends[j].edge == ends[i].edge) ++j;
    if (j - i == 2) {
      partner[ends[i].end] = ends[i + 1].end;
      partner[ends[i + 1].end] = ends[i].end;
    } else if (j - i == 1) {
      ++out.open_ends;
    } else {
      ++out.crowded_edges;
    }
    i = j;
  }
  std::vector<bool> used(points.size() / 2, false);
  for (std::uint32_t s = 0; s < used.size(); ++s) {
    if (used[s]) continue;
    Polygon loop;
    std::uint32_t enter = 2 * s;
    bool closed = false;
    while (true) {
      used[enter / 2] = true;
      const Point2& p = points[enter];
      if (loop.empty() || distance_squared(p, loop.back()) > kSamePoint * kSamePoint) loop.push_back(p);
      const std::uint32_t next = partner[enter ^ 1u];
      if (next == kNone) break;
      if (next / 2 == s) {
        closed = true;
        break;
      }
      if (used[next / 2]) break;
      enter = next;
    }
    if (!closed) continue;
    while (loop.size() > 1 && distance_squared(loop.front(), loop.back()) <= kSamePoint * kSamePoint)
      loop.pop_back();
    if (loop.size() < 3) continue;
    const double area = signed_area(loop);
    if (area == 0) continue;
    if (area < 0) std::reverse(loop.begin(), loop.end());
    out.loops.push_back(std::move(loop));
  }
}

// The indices of `keys` in ascending order of their values, equal values in the order of the
// indices: a radix sort, stable, of the doubles' bits made to sort as unsigned integers (the
// sign bit flipped, negative values' bits all flipped). Comparison sorts of a million triangles'
// heights took 0.6-0.8 G instructions, a sixth of a run; this one 6 passes of counting.
std::vector<std::uint32_t> order_by(const std::vector<double>& keys) {
  constexpr int kBits = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kBits;
  const std::size_t n = keys.size();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> from(n), to(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double key = keys[i] == 0 ? 0.0 : keys[i];  // -0 and +0 are one height
    std::uint64_t bits = 0;
    std::memcpy(&bits, &key, sizeof bits);
    bits = bits >> 63 ? ~bits : bits | (std::uint64_t{1} << 63);
    from[i] = {bits, static_cast<std::uint32_t>(i)};
  }
  for (int shift = 0; shift < 64; shift += kBits) {
    std::vector<std::size_t> start(kBuckets + 1, 0);
    for (const auto& k : from) ++start[((k.first >> shift) & (kBuckets - 1)) + 1];
    if (std::count(start.begin() + 1, start.end(), n) == 1) continue;  // one digit for all: nothing moves
    for (std::size_t b = 1; b <= kBuckets; ++b) start[b] += start[b - 1];
    for (const auto& k : from) to[start[(k.first >> shift) & (kBuckets - 1)]++] = k;
    from.swap(to);
  }
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = from[i].second;
  return order;
}

}  // namespace

MeshSlicer::MeshSlicer(const Mesh& mesh) : mesh_(mesh) {
  const std::size_t n = mesh.triangles.size();
  bottom_.resize(n);
  top_.resize(n);
  for (std::size_t t = 0; t < n; ++t) {
    const auto& tri = mesh.triangles[t];
    const double a = mesh.vertices[tri[0]].z, b = mesh.vertices[tri[1]].z, c = mesh.vertices[tri[2]].z;
    bottom_[t] = std::min({a, b, c});
    top_[t] = std::max({a, b, c});
  }
  by_bottom_ = order_by(bottom_);
}

void MeshSlicer::band(double lo, double hi) {
  lo_ = lo, hi_ = hi;
  std::erase_if(active_, [&](std::uint32_t t) { return top_[t] < lo; });
  for (; next_ < by_bottom_.size() && bottom_[by_bottom_[next_]] <= hi; ++next_)
    if (top_[by_bottom_[next_]] >= lo) active_.push_back(by_bottom_[next_]);
}

MeshSection MeshSlicer::section(double z) const {
  MeshSection out;
  std::vector<Point2> points;  // two per segment
  std::vector<SegmentEnd> ends;
  for (const std::uint32_t t : active_) {
    if (bottom_[t] >= z || top_[t] < z) continue;  // all above (a corner on the plane is above), or all below
    const auto& tri = mesh_.triangles[t];
    for (int k = 0; k < 3; ++k) {
      std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      if ((mesh_.vertices[a].z < z) == (mesh_.vertices[b].z < z)) continue;
      if (a > b) std::swap(a, b);  // the same arithmetic for both triangles of the edge: the same point
      const Vec3& p = mesh_.vertices[a];
      const Vec3& q = mesh_.vertices[b];
      const double f = (z - p.z) / (q.z - p.z);
      ends.push_back({edge_key(a, b), static_cast<std::uint32_t>(points.size())});
      points.push_back({p.x + (q.x - p.x) * f, p.y + (q.y - p.y) * f});
    }
  }
  join(points, ends, out);
  return out;
}

double MeshSlicer::band_lean() const {
  double lean = 0;
  for (const std::uint32_t t : active_) {
    const auto& tri = mesh_.triangles[t];
    const Vec3& a = mesh_.vertices[tri[0]];
    const Vec3& b = mesh_.vertices[tri[1]];
    const Vec3& c = mesh_.vertices[tri[2]];
    const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double across = std::sqrt(nx * nx + ny * ny);
    const double l = across > 0 ? std::fabs(nz) / across : kFlat + 1;
    if (l <= kFlat) lean = std::max(lean, l);
  }
  return lean;
}

}  // namespace gcode::procedural
