#include "gcode/procedural/outline_offset.hpp"

#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
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

double squared_distance_to_segment(const Point2& p, const Point2& a, const Point2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0;
  t = std::fmax(0, std::fmin(1, t));
  const double ex = p.x - a.x - t * dx, ey = p.y - a.y - t * dy;
  return ex * ex + ey * ey;
}

// Marks the points of loop[from..to] to keep (to at most the size, which stands for point 0).
void douglas_peucker(const Polygon& loop, std::size_t from, std::size_t to, double tolerance, std::vector<bool>& keep) {
  const std::size_t n = loop.size();
  std::vector<std::pair<std::size_t, std::size_t>> todo{{from, to}};
  while (!todo.empty()) {
    const auto [a, b] = todo.back();
    todo.pop_back();
    double worst = 0;
    std::size_t at = a;
    const Point2& pa = loop[a % n];
    const Point2& pb = loop[b % n];
    for (std::size_t i = a + 1; i < b; ++i) {  // b <= n: only b itself wraps round
      const double d = squared_distance_to_segment(loop[i], pa, pb);
      if (d > worst) worst = d, at = i;
    }
    if (worst <= tolerance * tolerance) continue;
    keep[at % n] = true;
    todo.push_back({a, at});
    todo.push_back({at, b});
  }
}


double cross(const Point2& a, const Point2& b) { return a.x * b.y - a.y * b.x; }

// Whether segments ab and cd meet (touching counts: the caller then asks Clipper).
bool segments_meet(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
  const Point2 ab{b.x - a.x, b.y - a.y}, cd{d.x - c.x, d.y - c.y};
  const double c1 = cross(ab, {c.x - a.x, c.y - a.y}), c2 = cross(ab, {d.x - a.x, d.y - a.y});
  const double c3 = cross(cd, {a.x - c.x, a.y - c.y}), c4 = cross(cd, {b.x - c.x, b.y - c.y});
  return (c1 <= 0) != (c2 < 0) && (c3 <= 0) != (c4 < 0);
}

// Whether the closed loop crosses itself: segments binned in square cells twice the mean segment
// long (sorted by cell), only segments sharing a cell compared: about n tests, not n squared.
bool crosses_itself(const Polygon& loop) {
  const std::size_t n = loop.size();
  double perimeter = 0;
  for (std::size_t i = 0; i < n; ++i)
    perimeter += distance(loop[i], loop[(i + 1) % n]);
  const double size = 2 * perimeter / static_cast<double>(n) + 1e-9;
  auto cell = [size](double v) { return static_cast<std::int64_t>(std::floor(v / size)); };
  std::vector<std::pair<std::int64_t, std::size_t>> binned;  // (cell, segment)
  binned.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& a = loop[i];
    const Point2& b = loop[(i + 1) % n];
    for (std::int64_t gx = cell(std::fmin(a.x, b.x)); gx <= cell(std::fmax(a.x, b.x)); ++gx)
      for (std::int64_t gy = cell(std::fmin(a.y, b.y)); gy <= cell(std::fmax(a.y, b.y)); ++gy)
        binned.push_back({gx * 2000003 + gy, i});
  }
  std::sort(binned.begin(), binned.end());
  for (std::size_t u = 0; u < binned.size(); ++u)
    for (std::size_t v = u + 1; v < binned.size() && binned[v].first == binned[u].first; ++v) {
      const std::size_t i = binned[u].second, j = binned[v].second;
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // neighbours share a corner
      if (segments_meet(loop[i], loop[(i + 1) % n], loop[j], loop[(j + 1) % n])) return true;
    }
  return false;
}

// The inward offset drawn directly, as Clipper's round offset would come out when nothing folds:
// every edge moved inward, neighbours meeting where the moved lines cross at a convex corner,
// an arc round a concave one. Most sections of a vase are such loops, and Clipper's general
// machinery (a sweep resolving the small loops it first draws at every convex corner) costs
// most of a run. Empty when an edge would turn back or the loop would cross itself: Clipper's case.
Polygon direct_offset(const Polygon& loop, double d, double arc_tolerance) {
  const std::size_t n = loop.size();
  std::vector<Point2> normal(n);  // of edge i (loop[i] to loop[i + 1]), pointing inside
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& a = loop[i];
    const Point2& b = loop[(i + 1) % n];
    const double len = distance(a, b);
    if (len == 0) return {};
    normal[i] = {-(b.y - a.y) / len, (b.x - a.x) / len};
  }
  // Points per radian of arc as Clipper takes them (its tolerance at most a quarter of the offset).
  const double y = std::fmin(arc_tolerance, d / 4);
  const double per_radian = 1 / (2 * std::acos(1 - y / d));
  Polygon out;
  out.reserve(n + n / 4);
  std::vector<std::size_t> first(n + 1), last(n);  // the points drawn for each corner
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& v = loop[i];
    const Point2& n1 = normal[(i + n - 1) % n];
    const Point2& n2 = normal[i];
    const double turn = cross(n1, n2), along = n1.x * n2.x + n1.y * n2.y;
    first[i] = out.size();
    const double angle = std::atan2(turn, along);
    const int steps = static_cast<int>(std::lround(per_radian * -angle));
    // Convex, straight, or a concave turn too slight for an arc point (the crossing then lies
    // within a quarter of the arc tolerance beyond the arc): the moved edges meet at their lines' crossing.
    if (steps < 1) {
      if (1 + along < 1e-6) return {};
      const double k = d / (1 + along);
      out.push_back({v.x + k * (n1.x + n2.x), v.y + k * (n1.y + n2.y)});
    } else {  // concave: round the corner at the distance
      for (int s = 0; s < steps; ++s) {
        const double t = angle * s / steps, c = std::cos(t), sn = std::sin(t);
        out.push_back({v.x + d * (n1.x * c - n1.y * sn), v.y + d * (n1.x * sn + n1.y * c)});
      }
      out.push_back({v.x + d * n2.x, v.y + d * n2.y});
    }
    last[i] = out.size() - 1;
  }
  first[n] = first[0];
  for (std::size_t i = 0; i < n; ++i) {  // a moved edge running backwards: the loop folds there
    const Point2& a = out[last[i]];
    const Point2& b = out[first[i + 1]];
    const Point2& p = loop[i];
    const Point2& q = loop[(i + 1) % n];
    if ((b.x - a.x) * (q.x - p.x) + (b.y - a.y) * (q.y - p.y) <= 0) return {};
  }
  if (loop_area(out) <= 0 || crosses_itself(out)) return {};
  return out;
}

}  // namespace

double loop_area(const Polygon& p) {
  double a = 0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += p[j].x * p[i].y - p[i].x * p[j].y;
  return a / 2;
}

std::vector<Polygon> offset_inward(const Polygon& loop, double distance, double arc_tolerance) {
  if (loop.size() >= 3 && distance > 0 && arc_tolerance > 0 && loop_area(loop) > 0) {
    Polygon direct = direct_offset(loop, distance, arc_tolerance);
    if (!direct.empty()) return {std::move(direct)};
  }
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
    const double d = distance_squared(loop[i], loop[0]);
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
