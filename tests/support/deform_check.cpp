// The independent checker of gc-deform (deform_check.hpp), compiled once
// into the test kit, at the kit's optimisation: the sanitizer tree builds the
// test files themselves at -O0, and the checker's nearest-segment searches
// are most of a deform test's time.
#include "deform_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "gcode/core/arc.hpp"
#include "test_support.hpp"

namespace deformtest {
namespace {

struct Segment {
  P3 a, b;          // image
  P3 pa, pb;        // pre-image (input path)
  double per_mm;    // the input move's filament per mm (0: travel)
};

double dist(const P3& a, const P3& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

// Distance from p to segment ab, and where along it (0..1).
double to_segment(const P3& p, const P3& a, const P3& b, double& t) {
  double d[3], q[3], l2 = 0, dot = 0;
  for (int i = 0; i < 3; ++i) d[i] = b[i] - a[i], q[i] = p[i] - a[i], l2 += d[i] * d[i], dot += q[i] * d[i];
  t = l2 > 0 ? std::clamp(dot / l2, 0.0, 1.0) : 0;
  return std::hypot(q[0] - t * d[0], q[1] - t * d[1], q[2] - t * d[2]);
}

// Segments by layer and 1 mm cell.
class Grid {
 public:
  void add(int layer, const Segment& s) {
    segments_.push_back(s);
    const double lo[2] = {std::min(s.a[0], s.b[0]), std::min(s.a[1], s.b[1])};
    const double hi[2] = {std::max(s.a[0], s.b[0]), std::max(s.a[1], s.b[1])};
    boxes_.push_back({lo[0], lo[1], hi[0], hi[1]});
    for (long i = cell(lo[0]); i <= cell(hi[0]); ++i)
      for (long j = cell(lo[1]); j <= cell(hi[1]); ++j) cells_[key(layer, i, j)].push_back(segments_.size() - 1);
  }
  // The nearest segment of `layer` within `reach` cells; null if none.
  // Ring by ring around p's cell, ending once every cell left lies farther
  // than the nearest so far: the answer of measuring every segment of the
  // (2 reach + 1)^2 cells, to the bit, first of equals included (in the
  // order of that scan: column, row, then the order segments were added).
  const Segment* nearest(int layer, const P3& p, double& d, double& t, long reach = 2) const {
    const Segment* best = nullptr;
    std::array<long long, 3> best_rank{};
    d = std::numeric_limits<double>::infinity();
    const long ci = cell(p[0]), cj = cell(p[1]);
    for (long r = 0; r <= reach; ++r) {
      for (long i = ci - r; i <= ci + r; ++i)
        for (long j = cj - r; j <= cj + r; ++j) {
          if (std::max(std::labs(i - ci), std::labs(j - cj)) != r) continue;
          auto it = cells_.find(key(layer, i, j));
          if (it == cells_.end()) continue;
          for (std::size_t k : it->second) {
            // A segment whose box is farther than the nearest so far cannot
            // replace it: skipped without its (costly) distance. The margin,
            // far above rounding, keeps equals in.
            const std::array<double, 4>& box = boxes_[k];
            const double bx = std::max({box[0] - p[0], 0.0, p[0] - box[2]});
            const double by = std::max({box[1] - p[1], 0.0, p[1] - box[3]});
            if (bx * bx + by * by > (d + 1e-9) * (d + 1e-9)) continue;
            double tk = 0;
            const double dk = to_segment(p, segments_[k].a, segments_[k].b, tk);
            if (dk > d) continue;
            // Where a full scan meets the segment first: the first cell of
            // its box inside the window, in column-then-row order.
            const std::array<long long, 3> rank{std::max(cell(box[0]), ci - reach), std::max(cell(box[1]), cj - reach),
                                                static_cast<long long>(k)};
            if (dk < d || rank < best_rank) d = dk, t = tk, best = &segments_[k], best_rank = rank;
          }
        }
      // A cell beyond the rings so far is at least this far from p.
      const double edge = std::min({p[0] - static_cast<double>(ci - r), static_cast<double>(ci + r + 1) - p[0],
                                    p[1] - static_cast<double>(cj - r), static_cast<double>(cj + r + 1) - p[1]});
      if (d < edge) break;
    }
    return best;
  }

 private:
  static long cell(double v) { return static_cast<long>(std::floor(v)); }
  static long long key(int layer, long i, long j) {
    return (static_cast<long long>(layer) << 40) ^ (static_cast<long long>(i + 100000) << 20) ^ (j + 100000);
  }
  std::vector<Segment> segments_;
  std::vector<std::array<double, 4>> boxes_;  // each segment's x-y box: lo x, lo y, hi x, hi y
  std::unordered_map<long long, std::vector<std::size_t>> cells_;
};

// Points every `step` mm along a replayed move (arcs on their circle), ends included.
std::vector<P3> samples(const gctest::ReplayedMove& m, const std::string& line_text, double step) {
  const gcode::Move& mv = m.move;
  const int n = std::max(1, static_cast<int>(std::ceil(mv.length / step)));
  std::vector<P3> out;
  gcode::Arc arc;
  if (mv.kind == gcode::MoveKind::Arc)
    arc = gcode::make_arc(gcode::Line::parse(line_text), mv.start[0], mv.start[1], mv.end[0], mv.end[1]);
  for (int k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) / n;
    P3 p{mv.start[0] + (mv.end[0] - mv.start[0]) * t, mv.start[1] + (mv.end[1] - mv.start[1]) * t,
         mv.start[2] + (mv.end[2] - mv.start[2]) * t};
    if (arc.valid) {
      const double a = arc.start_angle + arc.sweep * t;
      p[0] = arc.cx + arc.radius * std::cos(a), p[1] = arc.cy + arc.radius * std::sin(a);
    }
    out.push_back(p);
  }
  return out;
}

// The image of the pre-image segment p0-p1 as segments, finer where it bends
// (its midpoint 0.0005 mm off the chord), so a cusp (sqrt |y|) is drawn true.
template <typename Add>
void refine(const Map& map, const P3& p0, const P3& q0, const P3& p1, const P3& q1, int depth, const Add& add) {
  const P3 pm{(p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2, (p0[2] + p1[2]) / 2};
  const P3 qm = map(pm);
  double t = 0;
  if (depth < 14 && to_segment(qm, q0, q1, t) > 0.0005) {
    refine(map, p0, q0, pm, qm, depth + 1, add);
    refine(map, pm, qm, p1, q1, depth + 1, add);
    return;
  }
  add(p0, q0, p1, q1);
}

}  // namespace

DeformCheck check_deform(const std::string& input, const std::string& output, const Map& map, const Factor& section,
                         double tolerance) {
  DeformCheck c;
  const std::vector<std::string> in_lines = gctest::split_lines(input), out_lines = gctest::split_lines(output);
  const gctest::LinePlace in_place = gctest::places_of(input), out_place = gctest::places_of(output);
  Grid image, printed;
  std::vector<std::pair<int, P3>> image_points;  // (layer, point) of extrusions, for (b)
  for (const gctest::ReplayedMove& m : gctest::replay_moves(input)) {
    const int layer = in_place.layer[m.line_index];
    if (layer == 0 || !(m.move.length > 0)) continue;
    const double per_mm = m.move.extruding && m.move.filament > 0 ? m.move.filament / m.move.length : 0;
    const std::vector<P3> pre = samples(m, in_lines[m.line_index], 0.05);
    P3 prev = map(pre[0]);
    for (std::size_t k = 1; k < pre.size(); ++k) {
      const P3 q = map(pre[k]);
      refine(map, pre[k - 1], prev, pre[k], q, 0, [&](const P3& p0, const P3& q0, const P3& p1, const P3& q1) {
        image.add(layer, {q0, q1, p0, p1, per_mm});
        if (per_mm > 0) {
          const P3 mid{(p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2, (p0[2] + p1[2]) / 2};
          c.filament_expected += per_mm * section(mid) * dist(q0, q1);
          image_points.push_back({layer, q1});
        }
      });
      prev = q;
    }
  }
  const double area = 1;  // E and filament per mm are both in mm of filament
  for (const gctest::ReplayedMove& m : gctest::replay_moves(output)) {
    const int layer = out_place.layer[m.line_index];
    if (layer == 0 || !(m.move.length > 0)) continue;
    const std::vector<P3> pts = samples(m, out_lines[m.line_index], 0.05);
    if (!m.move.extruding) {
      double d0 = 0, t0 = 0;
      if (image.nearest(layer, pts.front(), d0, t0) == nullptr || d0 > tolerance) {
        ++c.entry_travels;
        continue;
      }
    }
    for (const P3& p : pts) {
      double d = 0, t = 0;
      if (image.nearest(layer, p, d, t) == nullptr) d = std::numeric_limits<double>::infinity();
      if (d > c.worst_out) c.worst_out = d, c.worst_out_line = m.line_index;
    }
    if (!(m.move.extruding && m.move.filament > 0)) continue;
    ++c.output_pieces;
    c.filament_out += m.move.filament;
    for (std::size_t k = 1; k < pts.size(); ++k) printed.add(layer, {pts[k - 1], pts[k], pts[k - 1], pts[k], 1});
    const P3 mid{(m.move.start[0] + m.move.end[0]) / 2, (m.move.start[1] + m.move.end[1]) / 2,
                 (m.move.start[2] + m.move.end[2]) / 2};
    double d = 0, t = 0;
    const Segment* s = image.nearest(layer, mid, d, t);
    if (s == nullptr || s->per_mm == 0) {
      ++c.off_extrusion;
      continue;
    }
    const P3 pre{s->pa[0] + (s->pb[0] - s->pa[0]) * t, s->pa[1] + (s->pb[1] - s->pa[1]) * t,
                 s->pa[2] + (s->pb[2] - s->pa[2]) * t};
    const double want = s->per_mm * section(pre) * m.move.length * area;
    c.worst_e = std::max(c.worst_e, std::fabs(m.move.filament - want) - (2.1e-5 + 2e-3 * want));
  }
  for (const auto& [layer, q] : image_points) {
    double d = 0, t = 0;
    if (printed.nearest(layer, q, d, t) == nullptr) d = std::numeric_limits<double>::infinity();
    c.worst_back = std::max(c.worst_back, d);
  }
  return c;
}

}  // namespace deformtest
