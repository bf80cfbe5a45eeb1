#include "gcode/litho/stl_writer.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace gcode::litho {

namespace {

struct Vertex {
  float x, y, z;
};

struct Grid {
  int columns;  // pieces along s (a cylinder's last one wraps to the first column)
  int rows;     // pieces along z
};

Grid grid_of(const HeightMap& map, const StlOptions& options) {
  const double nu = std::ceil(map.length() / options.resolution - 1e-9);
  const double nv = std::ceil(map.height() / options.resolution - 1e-9);
  if (nu > 1e9 || nv > 1e9) throw std::invalid_argument("--resolution is too fine for an STL");
  return {std::max(map.closed() ? 16 : 1, static_cast<int>(nu)), std::max(1, static_cast<int>(nv))};
}

void put_float(std::string& out, float f) {
  const auto bits = std::bit_cast<std::uint32_t>(f);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((bits >> (8 * i)) & 0xff));
}

// Appends triangles as 50-byte STL records; flips the winding for a
// cylinder, whose (s, depth) frame is mirrored against the plate's.
class TriangleSink {
 public:
  explicit TriangleSink(bool flip) : flip_(flip) {}
  void triangle(const Vertex& a, Vertex b, Vertex c) {
    if (flip_) std::swap(b, c);
    const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
    const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
    double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double n = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (n > 0) {
      nx /= n;
      ny /= n;
      nz /= n;
    }
    put_float(buffer_, static_cast<float>(nx));
    put_float(buffer_, static_cast<float>(ny));
    put_float(buffer_, static_cast<float>(nz));
    for (const Vertex* v : {&a, static_cast<const Vertex*>(&b), static_cast<const Vertex*>(&c)}) {
      put_float(buffer_, v->x);
      put_float(buffer_, v->y);
      put_float(buffer_, v->z);
    }
    buffer_.push_back(0);
    buffer_.push_back(0);
    ++count_;
  }
  // a, b, c, d counter-clockwise seen from outside (for a plate).
  void quad(const Vertex& a, const Vertex& b, const Vertex& c, const Vertex& d) {
    triangle(a, b, c);
    triangle(a, c, d);
  }
  void flush(const BytesOut& out, StlStats& stats) {
    stats.bytes += buffer_.size();
    out(buffer_);
    buffer_.clear();
  }
  std::uint32_t count() const { return count_; }

 private:
  bool flip_;
  std::string buffer_;
  std::uint32_t count_ = 0;
};

}  // namespace

void StlOptions::validate() const {
  if (!(std::isfinite(resolution) && resolution > 0)) throw std::invalid_argument("--resolution must be above 0");
  if (!std::isfinite(center_x) || !std::isfinite(center_y))
    throw std::invalid_argument("--center must be a position on the bed");
}

std::uint32_t litho_stl_triangles(const HeightMap& map, const StlOptions& options) {
  options.validate();
  const Grid g = grid_of(map, options);
  const auto nu = static_cast<std::uint64_t>(g.columns);
  const auto nv = static_cast<std::uint64_t>(g.rows);
  const std::uint64_t count = 4 * nu * nv + 4 * nu + (map.closed() ? 0 : 4 * nv);
  if (count > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument(fmt::format("--resolution {} mm makes {} triangles, more than an STL holds",
                                            options.resolution, count));
  return static_cast<std::uint32_t>(count);
}

StlStats write_litho_stl(const HeightMap& map, const StlOptions& options, const BytesOut& out) {
  const std::uint32_t total = litho_stl_triangles(map, options);
  const Grid g = grid_of(map, options);
  const bool closed = map.closed();
  const int points = closed ? g.columns : g.columns + 1;  // distinct columns of vertices
  auto column = [&](int i) { return closed ? i % g.columns : i; };

  StlStats stats;
  stats.triangles = total;
  std::string header(80, ' ');
  const std::string title = fmt::format("gc-litho {} lithophane {:.2f} x {:.2f} mm, binary STL",
                                        closed ? "cylinder" : "flat", map.length(), map.height());
  header.replace(0, std::min<std::size_t>(title.size(), 80), title.substr(0, 80));
  for (int i = 0; i < 4; ++i) header.push_back(static_cast<char>((total >> (8 * i)) & 0xff));
  stats.bytes += header.size();
  out(header);

  // Two rows of vertices at a time: the base surface and the picture surface.
  std::vector<Vertex> inner_lo(static_cast<std::size_t>(points)), outer_lo(inner_lo.size());
  std::vector<Vertex> inner_hi(inner_lo.size()), outer_hi(inner_lo.size());
  auto fill_row = [&](int j, std::vector<Vertex>& inner, std::vector<Vertex>& outer) {
    const double z = map.height() * j / g.rows;
    for (int i = 0; i < points; ++i) {
      const double s = map.length() * i / g.columns;
      const Point base = map.place(s, 0, options.center_x, options.center_y);
      const Point top = map.place(s, map.thickness(s, z), options.center_x, options.center_y);
      inner[static_cast<std::size_t>(i)] = {static_cast<float>(base.x), static_cast<float>(base.y), static_cast<float>(z)};
      outer[static_cast<std::size_t>(i)] = {static_cast<float>(top.x), static_cast<float>(top.y), static_cast<float>(z)};
    }
  };

  TriangleSink sink(closed);
  auto at = [](const std::vector<Vertex>& row, int i) -> const Vertex& { return row[static_cast<std::size_t>(i)]; };
  fill_row(0, inner_lo, outer_lo);
  for (int i = 0; i < g.columns; ++i) {  // bottom
    const int i1 = column(i + 1);
    sink.quad(at(inner_lo, i), at(outer_lo, i), at(outer_lo, i1), at(inner_lo, i1));
  }
  for (int j = 0; j < g.rows; ++j) {
    fill_row(j + 1, inner_hi, outer_hi);
    for (int i = 0; i < g.columns; ++i) {
      const int i1 = column(i + 1);
      sink.quad(at(inner_lo, i), at(inner_lo, i1), at(inner_hi, i1), at(inner_hi, i));  // base face
      sink.quad(at(outer_lo, i), at(outer_hi, i), at(outer_hi, i1), at(outer_lo, i1));  // picture face
    }
    if (!closed) {
      const int r = g.columns;
      sink.quad(at(inner_lo, 0), at(inner_hi, 0), at(outer_hi, 0), at(outer_lo, 0));  // left end
      sink.quad(at(inner_lo, r), at(outer_lo, r), at(outer_hi, r), at(inner_hi, r));  // right end
    }
    sink.flush(out, stats);
    std::swap(inner_lo, inner_hi);
    std::swap(outer_lo, outer_hi);
  }
  for (int i = 0; i < g.columns; ++i) {  // top
    const int i1 = column(i + 1);
    sink.quad(at(inner_lo, i), at(inner_lo, i1), at(outer_lo, i1), at(outer_lo, i));
  }
  sink.flush(out, stats);
  if (sink.count() != total) throw std::logic_error("write_litho_stl: triangle count does not match the header");
  return stats;
}

}  // namespace gcode::litho
