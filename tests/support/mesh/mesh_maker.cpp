#include "mesh_maker.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <numbers>
#include <random>

#include <fmt/format.h>

namespace meshtest {

namespace {

constexpr double kPi = std::numbers::pi;

using Ring = std::vector<P3>;

// Quads between neighbouring rings (same count, counter-clockwise seen from
// above), each as two triangles facing outward.
void stitch(const Ring& low, const Ring& high, std::vector<Tri>& out) {
  const std::size_t n = low.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    out.push_back({low[i], low[j], high[j]});
    out.push_back({low[i], high[j], high[i]});
  }
}

// A fan from the ring's centre: a floor (facing down) or a lid (facing up).
void cap(const Ring& ring, bool lid, std::vector<Tri>& out) {
  P3 c{0, 0, ring[0].z};
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const P3& a = ring[i];
    const P3& b = ring[(i + 1) % ring.size()];
    if (lid) out.push_back({c, a, b});
    else out.push_back({c, b, a});
  }
}

TestMesh revolve(std::string name, int rings, int around, double z0, double z1,
                 const std::function<double(double, double)>& radius, bool floor, bool lid) {
  TestMesh m{std::move(name), {}, z1 - z0};
  std::vector<Ring> all;
  for (int k = 0; k <= rings; ++k) {
    const double z = z0 + (z1 - z0) * k / rings;
    Ring ring;
    for (int i = 0; i < around; ++i) {
      const double a = 2 * kPi * i / around;
      const double r = radius(z, a);
      ring.push_back({r * std::cos(a), r * std::sin(a), z - z0});
    }
    all.push_back(std::move(ring));
  }
  for (int k = 0; k < rings; ++k) stitch(all[k], all[k + 1], m.triangles);
  if (floor) cap(all.front(), false, m.triangles);
  if (lid) cap(all.back(), true, m.triangles);
  return m;
}

void put_float(std::string& s, double v) {
  const float f = static_cast<float>(v);
  char b[4];
  std::memcpy(b, &f, 4);
  s.append(b, 4);
}

P3 normal_of(const Tri& t) {
  const double ux = t[1].x - t[0].x, uy = t[1].y - t[0].y, uz = t[1].z - t[0].z;
  const double vx = t[2].x - t[0].x, vy = t[2].y - t[0].y, vz = t[2].z - t[0].z;
  P3 n{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
  const double l = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  return l > 0 ? P3{n.x / l, n.y / l, n.z / l} : P3{};
}

}  // namespace

TestMesh cylinder(double radius, double height, int facets) {
  return revolve("cylinder", 1, facets, 0, height, [=](double, double) { return radius; }, true, true);
}

TestMesh wavy_vase(double height, int rings, int around) {
  return revolve(
      "wavy_vase", rings, around, 0, height,
      [=](double z, double a) { return 14 + 3 * std::sin(2 * kPi * z / height * 1.5) + 0.8 * std::cos(6 * a); }, true,
      false);
}

TestMesh twisted_prism(double half_side, double height, double twist_degrees, int rings) {
  TestMesh m{"twisted_prism", {}, height};
  std::vector<Ring> all;
  for (int k = 0; k <= rings; ++k) {
    const double z = height * k / rings;
    const double turn = twist_degrees * kPi / 180 * k / rings;
    Ring ring;
    for (int c = 0; c < 4; ++c) {
      const double a = turn + kPi / 4 + c * kPi / 2;
      const double r = half_side * std::sqrt(2.0);
      ring.push_back({r * std::cos(a), r * std::sin(a), z});
    }
    all.push_back(std::move(ring));
  }
  for (int k = 0; k < rings; ++k) stitch(all[k], all[k + 1], m.triangles);
  cap(all.front(), false, m.triangles);
  cap(all.back(), true, m.triangles);
  return m;
}

TestMesh star(double outer, double inner, double height, int points) {
  TestMesh m{"star", {}, height};
  Ring low, high;
  for (int i = 0; i < 2 * points; ++i) {
    const double a = kPi * i / points;
    const double r = i % 2 == 0 ? outer : inner;
    low.push_back({r * std::cos(a), r * std::sin(a), 0});
    high.push_back({r * std::cos(a), r * std::sin(a), height});
  }
  stitch(low, high, m.triangles);
  cap(low, false, m.triangles);
  cap(high, true, m.triangles);
  return m;
}

TestMesh sphere_shade(double radius, double from_degrees, double to_degrees, int rings, int around) {
  // Polar angle from the top: z = R cos(t), r = R sin(t); ring 0 is the lowest.
  const double t0 = to_degrees * kPi / 180, t1 = from_degrees * kPi / 180;
  TestMesh m{"sphere_shade", {}, 0};
  std::vector<Ring> all;
  const double zlow = radius * std::cos(t0);
  for (int k = 0; k <= rings; ++k) {
    const double t = t0 + (t1 - t0) * k / rings;
    Ring ring;
    for (int i = 0; i < around; ++i) {
      const double a = 2 * kPi * i / around;
      ring.push_back({radius * std::sin(t) * std::cos(a), radius * std::sin(t) * std::sin(a), radius * std::cos(t) - zlow});
    }
    all.push_back(std::move(ring));
  }
  for (int k = 0; k < rings; ++k) stitch(all[k], all[k + 1], m.triangles);
  m.height = radius * std::cos(t1) - zlow;
  return m;
}

std::string binary_stl(const TestMesh& mesh) {
  std::string s = "solid " + mesh.name;
  s.resize(80, ' ');
  const auto n = static_cast<std::uint32_t>(mesh.triangles.size());
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>((n >> (8 * i)) & 0xff));
  for (const Tri& t : mesh.triangles) {
    const P3 nn = normal_of(t);
    for (double v : {nn.x, nn.y, nn.z}) put_float(s, v);
    for (const P3& p : t)
      for (double v : {p.x, p.y, p.z}) put_float(s, v);
    s.append(2, '\0');
  }
  return s;
}

std::string sloppy_ascii_stl(const TestMesh& mesh, double jitter) {
  std::mt19937 random(42);
  std::uniform_real_distribution<double> noise(-jitter, jitter);
  std::string s = "solid " + mesh.name + " exported carelessly\n";
  for (const Tri& t : mesh.triangles) {
    const P3 n = normal_of(t);
    s += fmt::format("  facet normal {:e} {:e} {:e}\n    outer loop\n", -n.x, -n.y, -n.z);
    for (const P3& p : t)
      s += fmt::format("      vertex {:.7f} {:.7f} {:.7f}\n", p.x + noise(random), p.y + noise(random),
                       p.z + (p.z == 0 ? 0 : noise(random)));
    s += "    endloop\n  endfacet\n";
  }
  s += "endsolid " + mesh.name + "\n";
  return s;
}

}  // namespace meshtest
