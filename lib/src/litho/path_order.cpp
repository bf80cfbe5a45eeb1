#include "gcode/litho/path_order.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <utility>

namespace gcode::litho {

namespace {

double distance(Point a, Point b) { return std::hypot(b.x - a.x, b.y - a.y); }

Point end_of(const Path& path) { return path.pieces.empty() ? path.start : path.pieces.back().to; }

bool is_ring(const Path& path) {
  const Point e = end_of(path);
  return !path.pieces.empty() && e.x == path.start.x && e.y == path.start.y;
}

Point vertex_before(const Path& path, std::size_t piece) { return piece == 0 ? path.start : path.pieces[piece - 1].to; }

// The point of a path's line nearest to q: on piece `piece`, a share `u` of the way along it.
struct Spot {
  std::size_t piece = 0;
  double u = 0;
  double d = std::numeric_limits<double>::infinity();
};

Spot nearest_on(const Path& path, Point q) {
  Spot best;
  for (std::size_t j = 0; j < path.pieces.size(); ++j) {
    const Point a = vertex_before(path, j);
    const Point b = path.pieces[j].to;
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double len2 = dx * dx + dy * dy;
    const double u = len2 > 0 ? std::clamp(((q.x - a.x) * dx + (q.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
    const double d = distance(q, {a.x + u * dx, a.y + u * dy});
    if (d < best.d) best = {j, u, d};
  }
  return best;
}

// Cuts `path` at `spot` into the part before it and the part from it on.
void split(const Path& path, Spot spot, Path& head, Path& tail) {
  head = Path{};
  tail = Path{};
  head.role = tail.role = path.role;
  head.start = path.start;
  std::size_t j = spot.piece;
  if (spot.u > 1 - 1e-9) {
    ++j;
    spot.u = 0;
  }
  head.pieces.assign(path.pieces.begin(), path.pieces.begin() + static_cast<std::ptrdiff_t>(j));
  if (j == path.pieces.size()) {
    tail.start = end_of(path);
    return;
  }
  const Point a = vertex_before(path, j);
  const Piece& piece = path.pieces[j];
  if (spot.u < 1e-9) {
    tail.start = a;
    tail.pieces.assign(path.pieces.begin() + static_cast<std::ptrdiff_t>(j), path.pieces.end());
    return;
  }
  const Point cut{a.x + spot.u * (piece.to.x - a.x), a.y + spot.u * (piece.to.y - a.y)};
  Piece first = piece;
  first.to = cut;
  first.volume = piece.volume * spot.u;
  Piece second = piece;
  second.volume = piece.volume - first.volume;
  head.pieces.push_back(first);
  tail.start = cut;
  tail.pieces.push_back(second);
  tail.pieces.insert(tail.pieces.end(), path.pieces.begin() + static_cast<std::ptrdiff_t>(j) + 1, path.pieces.end());
}

// A closed loop made of `loop` (each path starting where the one before
// ends, the last ending on the first's start), started at its point nearest q.
void start_loop_near(std::vector<Path>& loop, Point q) {
  std::size_t k = 0;
  Spot best;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Spot s = nearest_on(loop[i], q);
    if (s.d < best.d) {
      best = s;
      k = i;
    }
  }
  if (loop.empty() || loop[k].pieces.empty()) return;
  Path head, tail;
  split(loop[k], best, head, tail);
  std::vector<Path> out;
  out.reserve(loop.size() + 1);
  if (loop.size() == 1) {  // a ring: one path again
    tail.pieces.insert(tail.pieces.end(), head.pieces.begin(), head.pieces.end());
    out.push_back(std::move(tail));
  } else {
    out.push_back(std::move(tail));
    for (std::size_t i = k + 1; i < loop.size(); ++i) out.push_back(std::move(loop[i]));
    for (std::size_t i = 0; i < k; ++i) out.push_back(std::move(loop[i]));
    out.push_back(std::move(head));
  }
  loop.clear();
  for (Path& p : out)
    if (!p.pieces.empty()) loop.push_back(std::move(p));
}

void reverse(Path& path) {
  Path r;
  r.role = path.role;
  r.start = end_of(path);
  r.pieces.reserve(path.pieces.size());
  for (std::size_t k = path.pieces.size(); k-- > 0;) {
    Piece p = path.pieces[k];
    p.to = vertex_before(path, k);
    r.pieces.push_back(p);
  }
  path = std::move(r);
}

// The travel from `from` to `path.start` inside the layer's band.
class Comber {
 public:
  Comber(const LithophanePlanner& planner, double z) : planner_(planner), map_(planner.map()), z_(z) {
    const LithoOptions& o = planner.options();
    cx_ = o.center_x;
    cy_ = o.center_y;
    step_ = o.resolution;
  }

  void route(Point from, Path& path) const {
    path.combed = true;
    path.from = from;
    path.approach.clear();
    const Point to = path.start;
    if (inside(from, to)) return;
    double sp = 0, dp = 0, sq = 0, dq = 0;
    map_.locate(from, cx_, cy_, sp, dp);
    map_.locate(to, cx_, cy_, sq, dq);
    double span = sq - sp;  // a cylinder goes the shorter way round
    if (map_.closed()) {
      const double length = map_.length();
      span -= length * std::round(span / length);
    }
    const int n = std::max(1, static_cast<int>(std::ceil(std::abs(span) / step_)));
    double thinnest = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i) thinnest = std::min(thinnest, map_.thickness(at(sp + span * i / n), z_));
    const double depth = thinnest / 2;
    int chords = 1;
    if (map_.closed()) {
      // Chords of the circle at `depth` sag inward by r (1 - cos(a / 2)): at most a quarter of depth.
      const double r = map_.base_radius() + depth;
      const double most = 2 * std::acos(1 - depth / (4 * r));
      chords = std::max(1, static_cast<int>(std::ceil(std::abs(span) / map_.base_radius() / most)));
    }
    for (int i = 0; i <= chords; ++i) add(path, planner_.point_at(at(sp + span * i / chords), depth));
  }

 private:
  double at(double s) const {
    if (!map_.closed()) return std::clamp(s, 0.0, map_.length());
    return s - map_.length() * std::floor(s / map_.length());
  }

  // Whether the straight line a-b stays in the band (every `step` along it).
  bool inside(Point a, Point b) const {
    const int n = std::max(1, static_cast<int>(std::ceil(distance(a, b) / step_)));
    for (int i = 0; i <= n; ++i) {
      const double f = static_cast<double>(i) / n;
      double s = 0, d = 0;
      map_.locate({a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f}, cx_, cy_, s, d);
      if (!map_.closed() && (s < 0 || s > map_.length())) return false;
      if (d < -1e-9 || d > map_.thickness(s, z_) + 1e-9) return false;
    }
    return true;
  }

  static void add(Path& path, Point p) {
    const Point last = path.approach.empty() ? path.from : path.approach.back();
    if (distance(last, p) > 1e-6 && distance(p, path.start) > 1e-6) path.approach.push_back(p);
  }

  const LithophanePlanner& planner_;
  const HeightMap& map_;
  double z_;
  double cx_ = 0, cy_ = 0, step_ = 0.2;
};

}  // namespace

void order_layer(const LithophanePlanner& planner, LithoLayer& layer, Point from) {
  std::vector<Path> walls, fill;
  for (Path& p : layer.paths) (p.role == PathRole::Fill ? fill : walls).push_back(std::move(p));
  layer.paths.clear();
  Point cur = from;
  // Walls: a flat plate's one loop, or a cylinder's rings one by one.
  if (planner.map().closed()) {
    for (Path& ring : walls) {
      std::vector<Path> loop;
      loop.push_back(std::move(ring));
      if (is_ring(loop[0])) start_loop_near(loop, cur);
      for (Path& p : loop) {
        cur = end_of(p);
        layer.paths.push_back(std::move(p));
      }
    }
  } else {
    start_loop_near(walls, cur);
    for (Path& p : walls) {
      cur = end_of(p);
      layer.paths.push_back(std::move(p));
    }
  }
  // Passes: nearest first.
  std::vector<bool> done(fill.size(), false);
  for (std::size_t left = fill.size(); left > 0; --left) {
    std::size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    bool flip = false;
    for (std::size_t i = 0; i < fill.size(); ++i) {
      if (done[i]) continue;
      if (is_ring(fill[i])) {
        const Spot s = nearest_on(fill[i], cur);
        if (s.d < best_d) {
          best_d = s.d;
          best = i;
          flip = false;
        }
        continue;
      }
      const double a = distance(cur, fill[i].start);
      const double b = distance(cur, end_of(fill[i]));
      if (std::min(a, b) < best_d) {
        best_d = std::min(a, b);
        best = i;
        flip = b < a;
      }
    }
    done[best] = true;
    Path& p = fill[best];
    if (is_ring(p)) {
      std::vector<Path> loop;
      loop.push_back(std::move(p));
      start_loop_near(loop, cur);
      p = std::move(loop[0]);
    } else if (flip) {
      reverse(p);
    }
    cur = end_of(p);
    layer.paths.push_back(std::move(p));
  }
  // Travel between them, inside the band.
  const Comber comber(planner, layer.sample_z);
  cur = from;
  for (Path& p : layer.paths) {
    comber.route(cur, p);
    cur = end_of(p);
  }
}

void plan_ordered_layer(const LithophanePlanner& planner, int index, LithoLayer& out, Point& head) {
  planner.plan_layer(index, out);
  if (out.paths.empty()) return;
  if (index == 0) head = out.paths.front().start;
  order_layer(planner, out, head);
  head = end_of(out.paths.back());
}

}  // namespace gcode::litho
