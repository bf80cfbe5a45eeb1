#include "gcode/litho/path_order.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <utility>

namespace gcode::litho {

namespace {

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
    way(from, path.start, path.approach);
  }

  // The waypoints between `from` and `to` (none: straight).
  void way(Point from, Point to, std::vector<Point>& out) const {
    out.clear();
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
    for (int i = 0; i <= chords; ++i) {
      const Point p = planner_.point_at(at(sp + span * i / chords), depth);
      const Point last = out.empty() ? from : out.back();
      if (distance(last, p) > 1e-6 && distance(p, to) > 1e-6) out.push_back(p);
    }
  }

 private:
  double at(double s) const {
    if (!map_.closed()) return std::clamp(s, 0.0, map_.length());
    return s - map_.length() * std::floor(s / map_.length());
  }

  // Whether the straight line a-b stays in the band. The band's surface is
  // straight between the picture's knots, so the line is checked at its
  // ends and where it crosses a knot; a cylinder's chord also where it comes
  // nearest the axis (its depth is convex along it, so the surface can only
  // be crossed at those points).
  bool inside(Point a, Point b) const {
    auto ok = [&](Point p) {
      double s = 0, d = 0;
      map_.locate(p, cx_, cy_, s, d);
      if (!map_.closed() && (s < -1e-9 || s > map_.length() + 1e-9)) return false;
      return d >= -1e-9 && d <= map_.thickness(s, z_) + 1e-9;
    };
    if (!ok(a) || !ok(b)) return false;
    double sa = 0, sb = 0, d = 0;
    map_.locate(a, cx_, cy_, sa, d);
    map_.locate(b, cx_, cy_, sb, d);
    const double ax = a.x - cx_, ay = a.y - cy_, bx = b.x - cx_, by = b.y - cy_;
    if (map_.closed()) {
      if (ax * bx + ay * by <= 0) return false;  // a quarter turn or more apart: not worth a chord
      const double len2 = (bx - ax) * (bx - ax) + (by - ay) * (by - ay);
      if (len2 > 0) {
        const double f = std::clamp(-(ax * (bx - ax) + ay * (by - ay)) / len2, 0.0, 1.0);
        if (!ok({a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)})) return false;
      }
      double lo = sa, hi = sb;
      if (std::abs(hi - lo) > map_.length() / 2) (lo < hi ? lo : hi) += map_.length();  // across the seam
      if (lo > hi) std::swap(lo, hi);
      knots_.clear();
      map_.knots(lo, hi, knots_);
      for (const double k : knots_) {
        const double angle = k / map_.base_radius();
        const double ux = std::cos(angle), uy = std::sin(angle);
        const double den = ux * (by - ay) - uy * (bx - ax);
        if (std::abs(den) < 1e-15) continue;
        const double f = -(ux * ay - uy * ax) / den;
        if (f >= 0 && f <= 1 && !ok({a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)})) return false;
      }
      return true;
    }
    knots_.clear();
    map_.knots(std::min(sa, sb), std::max(sa, sb), knots_);
    for (const double k : knots_) {
      const double f = (k - sa) / (sb - sa);
      if (!ok({a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)})) return false;
    }
    return true;
  }

  const LithophanePlanner& planner_;
  const HeightMap& map_;
  double z_;
  double cx_ = 0, cy_ = 0, step_ = 0.2;
  mutable std::vector<double> knots_;
};

// One way to print the passes: which path next, reversed or not.
struct Step {
  std::size_t index;
  bool flip;
};

// Nearest first among `pool` (indices into fill not yet done), from `cur`.
// Returns where the head ends; a ring ends where it starts, at its point nearest the head.
Point nearest_first(const std::vector<Path>& fill, const std::vector<std::size_t>& pool, Point cur,
                    std::vector<char>& done, std::vector<Step>& steps) {
  for (;;) {
    std::size_t best = fill.size();
    double best_d = std::numeric_limits<double>::infinity();
    bool flip = false;
    Point end = cur;
    for (const std::size_t i : pool) {
      if (done[i]) continue;
      if (is_ring(fill[i])) {
        const Spot s = nearest_on(fill[i], cur);
        if (s.d < best_d) {
          best_d = s.d;
          best = i;
          flip = false;
          const Point a = vertex_before(fill[i], s.piece), b = fill[i].pieces[s.piece].to;
          end = {a.x + s.u * (b.x - a.x), a.y + s.u * (b.y - a.y)};
        }
        continue;
      }
      const double a = distance(cur, fill[i].start);
      const double b = distance(cur, end_of(fill[i]));
      if (std::min(a, b) < best_d) {
        best_d = std::min(a, b);
        best = i;
        flip = b < a;
        end = flip ? fill[i].start : end_of(fill[i]);
      }
    }
    if (best == fill.size()) return cur;
    done[best] = 1;
    steps.push_back({best, flip});
    cur = end;
  }
}

// Where a run's ends lie on the band, for estimating travel.
struct Ends {
  double s[2], d[2];  // start, end
};

// The positions along the base where runs end or the head is, as the
// vertices of PassOrder::euler's graph: distinct beyond 1e-6, a cylinder's
// 0 and its length one position.
class BasePositions {
 public:
  BasePositions(const std::vector<Ends>& ends, double head_s, bool closed, double length)
      : closed_(closed), length_(length) {
    std::vector<double> pos;
    for (const Ends& e : ends) pos.insert(pos.end(), {e.s[0], e.s[1]});
    pos.push_back(head_s);
    std::sort(pos.begin(), pos.end());
    for (const double p : pos)
      if (at_.empty() || p - at_.back() > 1e-6) at_.push_back(p);
    if (closed && at_.size() > 1 && at_.front() + length - at_.back() <= 1e-6) at_.pop_back();
  }

  std::size_t size() const { return at_.size(); }
  bool closed() const { return closed_; }
  std::size_t vertex(double p) const {
    std::size_t i = static_cast<std::size_t>(std::lower_bound(at_.begin(), at_.end(), p - 1e-6) - at_.begin());
    if (i == at_.size()) i = 0;  // past the last: the first, round the circle
    return i;
  }
  // The distance along the base between two positions (a cylinder's the shorter way round).
  double gap(std::size_t a, std::size_t b) const {
    const double d = std::abs(at_[a] - at_[b]);
    return closed_ ? std::min(d, length_ - d) : d;
  }

 private:
  bool closed_;
  double length_;
  std::vector<double> at_;
};

// An edge of the graph: a run, or a travel (`run` past the last run).
struct Edge {
  std::size_t u, v;
  std::size_t run;
};

// The odd positions paired with neighbours, one left out, for the least
// travel: on a line by dynamic programming over them in order; on a circle
// the same from each start.
std::vector<std::pair<std::size_t, std::size_t>> pair_odd_positions(const std::vector<std::size_t>& odd,
                                                                     const BasePositions& positions) {
  const std::size_t m = odd.size();
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t rot = 0; rot < (positions.closed() ? m : 1); ++rot) {
    auto at = [&](std::size_t k) { return odd[(k + rot) % m]; };
    // f[k][left]: cheapest for the first k with `left` (0/1) of them left out.
    std::vector<std::array<double, 2>> f(m + 1, {std::numeric_limits<double>::infinity(),
                                                 std::numeric_limits<double>::infinity()});
    std::vector<std::array<char, 2>> how(m + 1, {0, 0});  // 1: k-1 left out, 2: k-2 paired with k-1
    f[0][0] = 0;
    for (std::size_t k = 1; k <= m; ++k)
      for (int left = 0; left < 2; ++left) {
        if (left == 1 && f[k - 1][0] < f[k][1]) {
          f[k][1] = f[k - 1][0];
          how[k][1] = 1;
        }
        if (k >= 2 && f[k - 2][left] + positions.gap(at(k - 2), at(k - 1)) < f[k][left]) {
          f[k][left] = f[k - 2][left] + positions.gap(at(k - 2), at(k - 1));
          how[k][left] = 2;
        }
      }
    if (m > 0 && f[m][1] < best) {
      best = f[m][1];
      pairs.clear();
      std::size_t k = m;
      int left = 1;
      while (k > 0) {
        if (how[k][left] == 1) {
          --k;
          left = 0;
        } else {
          pairs.push_back({at(k - 2), at(k - 1)});
          k -= 2;
        }
      }
    }
  }
  return pairs;
}

// Joins the parts of the graph the edges leave apart: the cheapest gaps
// between neighbouring positions in use (the head's too) of different parts,
// each a travel there and back (`travel`: the run of a travel edge).
void join_parts(const BasePositions& positions, std::size_t head, std::size_t travel, std::vector<Edge>& edges) {
  const std::size_t nv = positions.size();
  std::vector<std::size_t> part(nv);
  for (std::size_t v = 0; v < nv; ++v) part[v] = v;
  auto find = [&](std::size_t v) {
    while (part[v] != v) v = part[v] = part[part[v]];
    return v;
  };
  std::vector<char> used(nv, 0);
  used[head] = 1;
  for (const Edge& e : edges) {
    part[find(e.u)] = find(e.v);
    used[e.u] = used[e.v] = 1;
  }
  std::vector<std::pair<double, std::size_t>> joins;  // gap between vertex i and the next used one
  std::vector<std::size_t> live;
  for (std::size_t v = 0; v < nv; ++v)
    if (used[v]) live.push_back(v);
  for (std::size_t k = 0; k + (positions.closed() ? 0 : 1) < live.size(); ++k)
    joins.push_back({positions.gap(live[k], live[(k + 1) % live.size()]), k});
  std::sort(joins.begin(), joins.end());
  for (const auto& [d, k] : joins) {
    const std::size_t a = live[k], b = live[(k + 1) % live.size()];
    if (find(a) == find(b)) continue;
    part[find(a)] = find(b);
    edges.push_back({a, b, travel});
    edges.push_back({a, b, travel});
  }
}

// Hierholzer's algorithm from `head`: `walk` gets (vertex, edge taken to it;
// edges.size() for the start), last first. False when the edges are not one
// walk from the head.
bool euler_walk(const std::vector<Edge>& edges, std::size_t nv, std::size_t head,
                std::vector<std::pair<std::size_t, std::size_t>>& walk) {
  std::vector<std::vector<std::size_t>> adj(nv);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    adj[edges[i].u].push_back(i);
    if (edges[i].v != edges[i].u) adj[edges[i].v].push_back(i);
  }
  std::vector<char> gone(edges.size(), 0);
  std::vector<std::size_t> next(nv, 0);
  std::vector<std::pair<std::size_t, std::size_t>> stack{{head, edges.size()}};  // vertex, edge taken to it
  walk.clear();
  while (!stack.empty()) {
    const std::size_t v = stack.back().first;
    while (next[v] < adj[v].size() && gone[adj[v][next[v]]]) ++next[v];
    if (next[v] == adj[v].size()) {
      walk.push_back(stack.back());
      stack.pop_back();
      continue;
    }
    const std::size_t e = adj[v][next[v]];
    gone[e] = 1;
    stack.push_back({edges[e].u == v ? edges[e].v : edges[e].u, e});
  }
  return std::count(gone.begin(), gone.end(), 0) == 0;
}

// Several orders of the passes; the one with the least travel wins: an
// Euler path (see euler()); nearest first, starting with each of the runs
// nearest the head (either way round); and group by group along the base
// (a group: the runs side by side over one stretch, as the planner makes
// them), forward or backward (a cylinder's from the group nearest the head),
// nearest first inside each group (a serpentine). Travel is estimated along
// the base (around a cylinder, not across it), as the combed travel goes.
class PassOrder {
 public:
  PassOrder(const LithophanePlanner& planner, const std::vector<Path>& fill, Point head)
      : map_(planner.map()), fill_(fill) {
    const LithoOptions& o = planner.options();
    ends_.resize(fill.size());
    for (std::size_t i = 0; i < fill.size(); ++i) {
      map_.locate(fill[i].start, o.center_x, o.center_y, ends_[i].s[0], ends_[i].d[0]);
      map_.locate(end_of(fill[i]), o.center_x, o.center_y, ends_[i].s[1], ends_[i].d[1]);
    }
    map_.locate(head, o.center_x, o.center_y, head_s_, head_d_);
    // Groups: consecutive runs over the same stretch.
    for (std::size_t i = 0; i < fill.size(); ++i) {
      const auto same = [&](std::size_t j) {
        const double a0 = std::min(ends_[i].s[0], ends_[i].s[1]), b0 = std::max(ends_[i].s[0], ends_[i].s[1]);
        const double a1 = std::min(ends_[j].s[0], ends_[j].s[1]), b1 = std::max(ends_[j].s[0], ends_[j].s[1]);
        return std::abs(a0 - a1) < 1e-6 && std::abs(b0 - b1) < 1e-6;
      };
      if (groups_.empty() || !same(i - 1)) groups_.emplace_back();
      groups_.back().push_back(i);
    }
  }

  std::vector<Step> best() {
    std::vector<Step> best_steps, steps;
    double best_cost = std::numeric_limits<double>::infinity();
    auto consider = [&](double cost) {
      if (cost < best_cost) {
        best_cost = cost;
        best_steps = steps;
      }
    };
    // Nearest first, from each of the nearest few runs.
    std::vector<std::pair<double, Step>> firsts;
    for (std::size_t i = 0; i < fill_.size(); ++i)
      for (int e = 0; e < 2; ++e) firsts.push_back({travel(head_s_, head_d_, ends_[i].s[e], ends_[i].d[e]), {i, e == 1}});
    const std::size_t tries = std::min<std::size_t>(firsts.size(), 8);
    std::partial_sort(firsts.begin(), firsts.begin() + static_cast<std::ptrdiff_t>(tries), firsts.end(),
                      [](const auto& x, const auto& y) { return x.first < y.first; });
    for (std::size_t t = 0; t < tries; ++t) {
      reset(steps);
      take(firsts[t].second, steps);
      consider(greedy(all_, steps));
    }
    // Group by group, forward and backward.
    if (groups_.size() > 1) {
      for (int dir : {1, -1}) {
        reset(steps);
        std::size_t first = dir > 0 ? 0 : groups_.size() - 1;
        if (map_.closed()) first = nearest_group();
        const std::size_t n = groups_.size();
        for (std::size_t k = 0; k < n; ++k) greedy(groups_[dir > 0 ? (first + k) % n : (first + n - k) % n], steps);
        consider(cost_);
      }
    }
    // The fewest travel by parity: an Euler path.
    reset(steps);
    if (euler(steps)) consider(cost_);
    return best_steps;
  }

 private:
  // Travel estimate between two band points: along the base (and out).
  double travel(double s0, double d0, double s1, double d1) const {
    double ds = std::abs(s1 - s0);
    if (map_.closed()) {
      ds = std::min(ds, map_.length() - ds);
      ds *= 1 + (d0 + d1) / 2 / map_.base_radius();
    }
    return std::hypot(ds, d1 - d0);
  }

  void reset(std::vector<Step>& steps) {
    steps.clear();
    done_.assign(fill_.size(), 0);
    s_ = head_s_;
    d_ = head_d_;
    cost_ = 0;
    if (all_.size() != fill_.size()) {
      all_.resize(fill_.size());
      for (std::size_t i = 0; i < all_.size(); ++i) all_[i] = i;
    }
  }

  void take(Step st, std::vector<Step>& steps) {
    const Ends& e = ends_[st.index];
    const int in = st.flip ? 1 : 0;
    cost_ += travel(s_, d_, e.s[in], e.d[in]);
    s_ = e.s[1 - in];
    d_ = e.d[1 - in];
    done_[st.index] = 1;
    steps.push_back(st);
  }

  double greedy(const std::vector<std::size_t>& pool, std::vector<Step>& steps) {
    for (;;) {
      double best = std::numeric_limits<double>::infinity();
      Step pick{fill_.size(), false};
      for (const std::size_t i : pool) {
        if (done_[i]) continue;
        for (int e = 0; e < 2; ++e) {
          const double d = travel(s_, d_, ends_[i].s[e], ends_[i].d[e]);
          if (d < best) {
            best = d;
            pick = {i, e == 1};
          }
        }
      }
      if (pick.index == fill_.size()) return cost_;
      take(pick, steps);
    }
  }

  // Seen along the base, the runs are edges between the positions of their
  // ends (runs side by side over one stretch share both). A walk through all
  // of them from the head needs a travel wherever a position has an odd
  // number of run ends (the head counted once more), except at the one where
  // the walk ends: so the odd positions are paired by travel, neighbours in
  // order along the base (the cheapest pairing on a line or a circle), one
  // left out; parts the pairing leaves apart are joined by a travel there and
  // back; the walk is then an Euler path (Hierholzer's algorithm).
  bool euler(std::vector<Step>& steps) {
    const BasePositions at(ends_, head_s_, map_.closed(), map_.length());
    const std::size_t nv = at.size();
    const std::size_t travel = fill_.size();  // the run of a travel edge
    std::vector<Edge> edges;
    std::vector<int> degree(nv, 0);
    for (std::size_t i = 0; i < ends_.size(); ++i) {
      edges.push_back({at.vertex(ends_[i].s[0]), at.vertex(ends_[i].s[1]), i});
      ++degree[edges.back().u];
      ++degree[edges.back().v];
    }
    const std::size_t head = at.vertex(head_s_);
    std::vector<std::size_t> odd;
    for (std::size_t v = 0; v < nv; ++v)
      if ((degree[v] + (v == head)) % 2) odd.push_back(v);
    for (const auto& [a, b] : pair_odd_positions(odd, at)) edges.push_back({a, b, travel});
    join_parts(at, head, travel, edges);
    std::vector<std::pair<std::size_t, std::size_t>> walk;
    if (!euler_walk(edges, nv, head, walk)) return false;  // not one walk: leave it to the others
    std::size_t from = head;
    for (std::size_t k = walk.size(); k-- > 0;) {
      const auto [v, e] = walk[k];
      if (e == edges.size()) continue;
      if (edges[e].run < travel) take({edges[e].run, at.vertex(ends_[edges[e].run].s[0]) != from}, steps);
      from = v;
    }
    return steps.size() == fill_.size();
  }

  std::size_t nearest_group() const {
    std::size_t first = 0;
    double near = std::numeric_limits<double>::infinity();
    for (std::size_t g = 0; g < groups_.size(); ++g)
      for (const std::size_t i : groups_[g])
        for (int e = 0; e < 2; ++e) {
          const double d = travel(head_s_, head_d_, ends_[i].s[e], ends_[i].d[e]);
          if (d < near) {
            near = d;
            first = g;
          }
        }
    return first;
  }

  const HeightMap& map_;
  const std::vector<Path>& fill_;
  std::vector<Ends> ends_;
  std::vector<std::vector<std::size_t>> groups_;
  std::vector<std::size_t> all_;
  std::vector<char> done_;
  double head_s_ = 0, head_d_ = 0, s_ = 0, d_ = 0, cost_ = 0;
};

// The order of the passes for a head at `cur`; closed rings (a cylinder whose
// count of passes is the same all round) nearest first, each from its point
// nearest the head.
std::vector<Step> order_passes(const LithophanePlanner& planner, const std::vector<Path>& fill, Point cur) {
  if (std::any_of(fill.begin(), fill.end(), is_ring)) {
    std::vector<Step> steps;
    std::vector<char> done(fill.size(), 0);
    std::vector<std::size_t> all(fill.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    nearest_first(fill, all, cur, done, steps);
    return steps;
  }
  return PassOrder(planner, fill, cur).best();
}

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
  // Passes: the order with the least travel of those PassOrder tries (an
  // Euler path, nearest first, group by group).
  const std::vector<Step> best_steps = order_passes(planner, fill, cur);
  for (const Step& st : best_steps) {
    Path& p = fill[st.index];
    if (is_ring(p)) {
      std::vector<Path> loop;
      loop.push_back(std::move(p));
      start_loop_near(loop, cur);
      p = std::move(loop[0]);
    } else if (st.flip) {
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
