#include "gcode/procedural/outline_offset.hpp"

#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace gcode::procedural {

namespace {

constexpr double kScale = 1e5;  // Clipper's integer unit: 10 nm

ClipperLib::Path to_clipper(const Polygon& loop) {
  ClipperLib::Path path;
  path.reserve(loop.size());
  for (const Point2& p : loop)
    path.push_back({static_cast<ClipperLib::cInt>(std::llround(p.x * kScale)),
                    static_cast<ClipperLib::cInt>(std::llround(p.y * kScale))});
  return path;
}

Polygon from_clipper(const ClipperLib::Path& path) {
  Polygon loop;
  loop.reserve(path.size());
  for (const ClipperLib::IntPoint& p : path) loop.push_back({p.X / kScale, p.Y / kScale});
  return loop;
}

double distance_to_segment(const Point2& p, const Point2& a, const Point2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0;
  t = std::fmax(0, std::fmin(1, t));
  return std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

// Marks the points of loop[from..to] (indices modulo the size) to keep.
void douglas_peucker(const Polygon& loop, std::size_t from, std::size_t to, double tolerance, std::vector<bool>& keep) {
  const std::size_t n = loop.size();
  std::vector<std::pair<std::size_t, std::size_t>> todo{{from, to}};
  while (!todo.empty()) {
    const auto [a, b] = todo.back();
    todo.pop_back();
    double worst = 0;
    std::size_t at = a;
    for (std::size_t i = a + 1; i < b; ++i) {
      const double d = distance_to_segment(loop[i % n], loop[a % n], loop[b % n]);
      if (d > worst) worst = d, at = i;
    }
    if (worst <= tolerance) continue;
    keep[at % n] = true;
    todo.push_back({a, at});
    todo.push_back({at, b});
  }
}

}  // namespace

double loop_area(const Polygon& p) {
  double a = 0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += p[j].x * p[i].y - p[i].x * p[j].y;
  return a / 2;
}

std::vector<Polygon> offset_inward(const Polygon& loop, double distance, double arc_tolerance) {
  ClipperLib::ClipperOffset offset(2, arc_tolerance * kScale);
  offset.AddPath(to_clipper(loop), ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  ClipperLib::Paths pieces;
  offset.Execute(pieces, -distance * kScale);
  std::vector<Polygon> out;
  for (const ClipperLib::Path& piece : pieces) {
    Polygon p = from_clipper(piece);
    if (p.size() < 3) continue;
    if (loop_area(p) < 0) std::reverse(p.begin(), p.end());
    out.push_back(std::move(p));
  }
  return out;
}

Polygon simplify_loop(const Polygon& loop, double tolerance) {
  const std::size_t n = loop.size();
  if (n <= 4) return loop;
  // Split the loop at its first point and the point farthest from it.
  std::size_t far = 0;
  double best = -1;
  for (std::size_t i = 1; i < n; ++i) {
    const double d = std::hypot(loop[i].x - loop[0].x, loop[i].y - loop[0].y);
    if (d > best) best = d, far = i;
  }
  std::vector<bool> keep(n, false);
  keep[0] = keep[far] = true;
  douglas_peucker(loop, 0, far, tolerance, keep);
  douglas_peucker(loop, far, n, tolerance, keep);
  Polygon out;
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) out.push_back(loop[i]);
  return out;
}

}  // namespace gcode::procedural
