#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "gcode/litho/stl_writer.hpp"
#include "litho_support.hpp"

using gcode::litho::HeightMap;
using gcode::litho::HeightMapOptions;
using gcode::litho::LithoShape;
using gcode::litho::StlOptions;

namespace {

using Key = std::array<std::uint32_t, 3>;  // a vertex by its float bits: shared vertices are bit-identical

struct Mesh {
  std::uint32_t declared = 0;
  std::vector<std::array<std::array<float, 3>, 3>> triangles;
  std::vector<std::array<float, 3>> normals;
};

float read_float(const char* p) {
  std::uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) bits |= static_cast<std::uint32_t>(static_cast<unsigned char>(p[i])) << (8 * i);
  float f = 0;
  std::memcpy(&f, &bits, 4);
  return f;
}

Mesh parse_stl(const std::string& bytes) {
  Mesh m;
  REQUIRE(bytes.size() >= 84);
  REQUIRE(bytes.compare(0, 5, "solid") != 0);  // readers take "solid" for ASCII STL
  for (int i = 0; i < 4; ++i)
    m.declared |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[80 + static_cast<std::size_t>(i)])) << (8 * i);
  REQUIRE(bytes.size() == 84 + 50 * static_cast<std::size_t>(m.declared));
  for (std::size_t t = 0; t < m.declared; ++t) {
    const char* p = bytes.data() + 84 + 50 * t;
    m.normals.push_back({read_float(p), read_float(p + 4), read_float(p + 8)});
    std::array<std::array<float, 3>, 3> tri{};
    for (int v = 0; v < 3; ++v)
      for (int c = 0; c < 3; ++c) tri[static_cast<std::size_t>(v)][static_cast<std::size_t>(c)] = read_float(p + 12 + 12 * v + 4 * c);
    m.triangles.push_back(tri);
  }
  return m;
}

Key key_of(const std::array<float, 3>& v) {
  Key k{};
  for (std::size_t c = 0; c < 3; ++c) std::memcpy(&k[c], &v[c], 4);
  return k;
}

// Every directed edge once, and its reverse once: closed and consistently oriented.
bool closed_and_oriented(const Mesh& m, std::string& why) {
  std::map<std::pair<Key, Key>, int> edges;
  for (const auto& t : m.triangles)
    for (std::size_t e = 0; e < 3; ++e) ++edges[{key_of(t[e]), key_of(t[(e + 1) % 3])}];
  for (const auto& [edge, count] : edges) {
    if (count != 1) {
      why = "a directed edge used " + std::to_string(count) + " times";
      return false;
    }
    if (edges.find({edge.second, edge.first}) == edges.end()) {
      why = "an edge with one triangle";
      return false;
    }
  }
  return true;
}

double signed_volume(const Mesh& m) {
  const auto& o = m.triangles.front()[0];  // a nearby origin keeps float coordinates from cancelling
  double v = 0;
  for (const auto& t : m.triangles) {
    double a[3], b[3], c[3];
    for (std::size_t i = 0; i < 3; ++i) {
      a[i] = double(t[0][i]) - o[i];
      b[i] = double(t[1][i]) - o[i];
      c[i] = double(t[2][i]) - o[i];
    }
    v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return v / 6;
}

// The solid's volume by independent integration of the height map on a fine grid.
double map_volume(const HeightMap& map) {
  const int nu = static_cast<int>(map.length() / 0.05), nv = static_cast<int>(map.height() / 0.05);
  double v = 0;
  const double r = map.base_radius();
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double t = map.thickness((i + 0.5) * map.length() / nu, (j + 0.5) * map.height() / nv);
      const double area = map.closed() ? ((r + t) * (r + t) - r * r) / 2 * (2 * std::numbers::pi / nu)
                                       : t * map.length() / nu;
      v += area * map.height() / nv;
    }
  return v;
}

struct Written {
  std::string bytes;
  std::size_t chunks = 0;
  gcode::litho::StlStats stats;
};

Written write(const HeightMap& map, const StlOptions& options = {}) {
  Written w;
  w.stats = gcode::litho::write_litho_stl(map, options, [&](std::string_view chunk) {
    w.bytes.append(chunk);
    ++w.chunks;
  });
  return w;
}

}  // namespace

TEST_CASE("litho STL: a flat lithophane STL is closed oriented outward and holds the height map's volume", "[litho][stl]") {
  HeightMapOptions o;
  o.width = 30;
  const HeightMap map(littest::strokes(60, 40), o);
  const Written w = write(map);
  const Mesh m = parse_stl(w.bytes);
  CHECK(m.declared == gcode::litho::litho_stl_triangles(map, {}));
  CHECK(w.stats.triangles == m.declared);
  CHECK(w.stats.bytes == w.bytes.size());
  std::string why;
  CHECK(closed_and_oriented(m, why));
  INFO(why);
  const double volume = signed_volume(m);
  CHECK(volume > 0);  // outward normals
  CHECK(volume == Approx(map_volume(map)).epsilon(0.005));
  // The stored normals agree with the winding.
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    const double ux = tri[1][0] - tri[0][0], uy = tri[1][1] - tri[0][1], uz = tri[1][2] - tri[0][2];
    const double vx = tri[2][0] - tri[0][0], vy = tri[2][1] - tri[0][1], vz = tri[2][2] - tri[0][2];
    const double dot = (uy * vz - uz * vy) * m.normals[t][0] + (uz * vx - ux * vz) * m.normals[t][1] +
                       (ux * vy - uy * vx) * m.normals[t][2];
    REQUIRE(dot > 0);
  }
  // Same place as the G-code: centred on X, base face max/2 in front of the centre, from the bed up.
  float lo[3] = {1e9f, 1e9f, 1e9f}, hi[3] = {-1e9f, -1e9f, -1e9f};
  for (const auto& t : m.triangles)
    for (const auto& v : t)
      for (std::size_t c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], v[c]);
        hi[c] = std::max(hi[c], v[c]);
      }
  CHECK(lo[0] == Approx(95));
  CHECK(hi[0] == Approx(125));
  CHECK(lo[1] == Approx(110 - 1.5));
  CHECK(hi[1] == Approx(110 + 1.5));
  CHECK(lo[2] == 0);
  CHECK(hi[2] == Approx(20));
  // One chunk a grid row (plus header and the top).
  CHECK(w.chunks == 100 + 2);
}

TEST_CASE("litho STL: a cylinder lithophane STL is a closed tube with the band's volume", "[litho][stl]") {
  HeightMapOptions o;
  o.shape = LithoShape::Cylinder;
  o.diameter = 30;
  o.height = 12;
  const HeightMap map(littest::gradient(64, 16), o);
  StlOptions so;
  so.resolution = 0.3;
  const Written w = write(map, so);
  const Mesh m = parse_stl(w.bytes);
  std::string why;
  CHECK(closed_and_oriented(m, why));
  INFO(why);
  const double volume = signed_volume(m);
  CHECK(volume > 0);
  CHECK(volume == Approx(map_volume(map)).epsilon(0.005));
}

TEST_CASE("litho STL: an STL resolution that would overflow the triangle count is refused", "[litho][stl]") {
  const HeightMap map(littest::gradient(8, 8), HeightMapOptions{});
  StlOptions o;
  o.resolution = 0.0001;
  CHECK_THROWS_WITH(gcode::litho::litho_stl_triangles(map, o), Catch::Contains("more than an STL holds"));
  o.resolution = 0;
  CHECK_THROWS_WITH(gcode::litho::litho_stl_triangles(map, o), Catch::Contains("--resolution"));
}
