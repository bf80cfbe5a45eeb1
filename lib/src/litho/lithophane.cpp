#include "gcode/litho/lithophane.hpp"

#include "gcode/litho/pass_counts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace gcode::litho {

namespace {

bool positive(double v) { return std::isfinite(v) && v > 0; }

void require_positive(double v, const char* option) {
  if (!positive(v)) throw std::invalid_argument(fmt::format("{} must be a number above 0", option));
}

}  // namespace

LithoOptions LithoOptions::resolved() const {
  LithoOptions r = *this;
  if (r.line_width == 0) r.line_width = r.nozzle * 1.125;
  if (r.max_pass_width == 0) r.max_pass_width = r.nozzle * 2.5;
  if (r.min_pass_width == 0) r.min_pass_width = r.nozzle * 0.5;
  return r;
}

void LithoOptions::validate(const HeightMapOptions& map) const {
  const LithoOptions r = resolved();
  require_positive(r.layer_height, "--layer-height");
  require_positive(r.nozzle, "--nozzle");
  require_positive(r.line_width, "--line-width");
  require_positive(r.filament_diameter, "--filament-diameter");
  require_positive(r.wall_speed, "--wall-speed");
  if (!(std::isfinite(r.infill_speed) && r.infill_speed >= 0))
    throw std::invalid_argument("--infill-speed must be 0 (the passes at --max-flow) or above");
  require_positive(r.max_flow, "--max-flow");
  require_positive(r.min_speed, "--min-speed");
  require_positive(r.max_speed, "--max-speed");
  require_positive(r.max_pass_width, "--max-pass-width");
  require_positive(r.min_pass_width, "--min-pass-width");
  require_positive(r.resolution, "--resolution");
  require_positive(r.edge_gap, "the gap left beside a bead");
  require_positive(r.surface_tolerance, "the surface tolerance");
  require_positive(r.min_piece, "the shortest piece");
  if (!(r.first_layer_factor > 0 && r.first_layer_factor <= 1))
    throw std::invalid_argument("the first-layer speed factor must be above 0 and at most 1");
  if (!std::isfinite(r.center_x) || !std::isfinite(r.center_y))
    throw std::invalid_argument("--center must be a position on the bed");
  if (!(r.min_speed < r.max_speed))
    throw std::invalid_argument(
        fmt::format("--min-speed ({} mm/s) must be less than --max-speed ({} mm/s)", r.min_speed, r.max_speed));
  if (!(r.min_pass_width < r.max_pass_width))
    throw std::invalid_argument(fmt::format("--min-pass-width ({} mm) must be less than --max-pass-width ({} mm)",
                                            r.min_pass_width, r.max_pass_width));
  if (!(r.layer_height < r.nozzle))
    throw std::invalid_argument(
        fmt::format("--layer-height ({} mm) must be less than the nozzle ({} mm)", r.layer_height, r.nozzle));
  if (r.line_width < 0.5 * r.nozzle || r.line_width > 2 * r.nozzle)
    throw std::invalid_argument(fmt::format("--line-width ({} mm) must be between half and twice the nozzle ({} mm)",
                                            r.line_width, r.nozzle));
  if (map.min_thickness < r.nozzle)
    throw std::invalid_argument(
        fmt::format("--min ({} mm) must be at least the nozzle ({} mm): each of the two walls needs half a nozzle",
                    map.min_thickness, r.nozzle));
}

LithophanePlanner::LithophanePlanner(const HeightMap& map, const LithoOptions& options)
    : map_(map), options_(options.resolved()) {
  options_.validate(map.options());
  const double lw = options_.line_width;
  const double h = options_.layer_height;
  if (!map.closed() && !(map.length() > 2 * lw + options_.resolution))
    throw std::invalid_argument(fmt::format("a {:.2f} mm wide plate leaves no room between its walls", map.length()));
  if (map.height() < h)
    throw std::invalid_argument(
        fmt::format("the lithophane ({:.2f} mm) is lower than one layer ({} mm)", map.height(), h));
  layers_ = std::max(1, static_cast<int>(std::lround(map.height() / h)));
  fill_rate_ = options_.infill_speed > 0 ? std::min(lw * h * options_.infill_speed, options_.max_flow) : options_.max_flow;
  wall_rate_ = std::min(lw * h * options_.wall_speed, options_.max_flow);
  const double r = options_.filament_diameter / 2;
  filament_area_ = std::numbers::pi * r * r;
}

Point LithophanePlanner::point_at(double s, double depth) const {
  return map_.place(s, depth, options_.center_x, options_.center_y);
}

LithophanePlanner::Column LithophanePlanner::column(double s, double z) const {
  const double t = map_.thickness(s, z);
  const double lw = options_.line_width;
  if (t - 2 * lw >= options_.min_pass_width) return {t, lw, t - 2 * lw};
  return {t, t / 2, 0};
}

// A piece that continues the previous one in a straight line at the same
// width and speed is the same bead: it extends it (an inner wall along a
// flat base, passes over a uniform part), which keeps the G-code short.
void LithophanePlanner::push_piece(Path& path, const Piece& piece) {
  if (!path.pieces.empty()) {
    Piece& last = path.pieces.back();
    const Point from = path.pieces.size() > 1 ? path.pieces[path.pieces.size() - 2].to : path.start;
    const double ax = last.to.x - from.x, ay = last.to.y - from.y;
    const double bx = piece.to.x - last.to.x, by = piece.to.y - last.to.y;
    const double along = ax * bx + ay * by;
    const double off_line = std::abs(ax * by - ay * bx) / std::hypot(ax, ay);  // distance of the new end from the line
    if (along > 0 && off_line < 1e-6 && std::abs(piece.width - last.width) <= 1e-9 * last.width &&
        std::abs(piece.speed - last.speed) <= 1e-9 * last.speed && piece.clamped == last.clamped) {
      last.to = piece.to;
      last.volume += piece.volume;
      return;
    }
  }
  path.pieces.push_back(piece);
}

double LithophanePlanner::clamp_speed(double speed, Piece& piece, LayerStats& stats) const {
  if (speed > options_.max_speed) {
    piece.clamped = true;
    ++stats.clamped_fast;
    return options_.max_speed;
  }
  if (speed < options_.min_speed) {
    piece.clamped = true;
    ++stats.clamped_slow;
    return options_.min_speed;
  }
  return speed;
}

bool LithophanePlanner::add_strip(const Strip& st, double rate, Path& path, LayerStats& stats) const {
  const Point p0 = point_at(st.s0, (st.a0 + st.b0) / 2);
  const Point p1 = point_at(st.s1, (st.a1 + st.b1) / 2);
  const double length = distance(p0, p1);
  if (length < 1e-9) return false;
  // Strip area by Simpson's rule over s; exact here, since the depths are
  // linear in s and a cylinder's area element (R + d) / R is linear in d.
  const double radius = map_.base_radius();
  auto depth_area = [&](double a, double b) { return (b - a) * (radius > 0 ? (radius + (a + b) / 2) / radius : 1.0); };
  const double f0 = depth_area(st.a0, st.b0);
  const double f1 = depth_area(st.a1, st.b1);
  const double fm = depth_area((st.a0 + st.a1) / 2, (st.b0 + st.b1) / 2);
  const double area = std::abs(st.s1 - st.s0) * (f0 + 4 * fm + f1) / 6;
  if (!(area > 0)) return false;
  Piece piece;
  piece.to = p1;
  piece.width = area / length;
  piece.volume = area * options_.layer_height;
  piece.speed = clamp_speed(rate / (piece.width * options_.layer_height), piece, stats);
  push_piece(path, piece);
  stats.band_area += area;
  stats.volume += piece.volume;
  ++stats.pieces;
  if (path.role == PathRole::Fill) ++stats.fill_pieces;
  return true;
}

// A flat plate's end cap: a wall bead across the thickness, at right angles to the walls.
void LithophanePlanner::add_cap(Point from, Point to, double rate, Path& path, LayerStats& stats) const {
  const double length = distance(from, to);
  if (length < 1e-9) return;
  Piece piece;
  piece.to = to;
  piece.width = options_.line_width;
  piece.volume = piece.width * length * options_.layer_height;
  piece.speed = clamp_speed(rate / (piece.width * options_.layer_height), piece, stats);
  push_piece(path, piece);
  stats.band_area += piece.width * length;
  stats.volume += piece.volume;
  ++stats.pieces;
}

// A pass's strip as `parts` equal pieces (its depths are linear along it).
void LithophanePlanner::add_fill_strip(const Strip& st, int parts, double rate, Path& path, LayerStats& stats) const {
  for (int p = 0; p < parts; ++p) {
    const double f0 = static_cast<double>(p) / parts, f1 = static_cast<double>(p + 1) / parts;
    auto at = [&](double f, double v0, double v1) { return v0 + (v1 - v0) * f; };
    add_strip({at(f0, st.s0, st.s1), at(f0, st.a0, st.a1), at(f0, st.b0, st.b1), at(f1, st.s0, st.s1),
               at(f1, st.a0, st.a1), at(f1, st.b0, st.b1)},
              rate, path, stats);
  }
}

// Douglas-Peucker over the candidate sample points (every resolution step
// and every pixel centre, in order; the first and last are kept): a point
// stays where the chord of the thickness through the kept points around it
// misses it by more than the surface tolerance, where the stretch would be
// longer than the longest piece, or where the pass count differs at the
// stretch's ends (so that a stretch has one count of passes). `keep` marks them.
void LithophanePlanner::keep_points(const std::vector<double>& cand, double z, std::vector<char>& keep) const {
  const std::size_t n = cand.size();
  keep.assign(n, 0);
  if (n == 0) return;
  keep.front() = keep.back() = 1;
  const double tol = options_.surface_tolerance;
  const double longest = longest_piece();
  auto passes = [&](double s) {
    const double g = column(s, z).gap;
    return g > 0 ? static_cast<int>(std::ceil(g / options_.max_pass_width - 1e-9)) : 0;
  };
  std::vector<std::size_t> stack{0, n - 1};
  while (!stack.empty()) {
    const std::size_t hi = stack.back();
    stack.pop_back();
    const std::size_t lo = stack.back();
    stack.pop_back();
    if (hi - lo < 2) continue;
    const double a = cand[lo], b = cand[hi];
    const double ta = map_.thickness(a, z), tb = map_.thickness(b, z);
    double worst = tol;
    std::size_t at = hi;
    for (std::size_t i = lo + 1; i < hi; ++i) {
      // A point within min piece of a kept one would make a sliver of a piece.
      if (cand[i] - a < options_.min_piece || b - cand[i] < options_.min_piece) continue;
      const double dev = std::abs(map_.thickness(cand[i], z) - (ta + (tb - ta) * (cand[i] - a) / (b - a)));
      if (dev > worst) {
        worst = dev;
        at = i;
      }
    }
    if (at == hi && (b - a > longest || passes(a) != passes(b))) {
      double best = std::numeric_limits<double>::infinity();  // the point nearest the middle
      for (std::size_t i = lo + 1; i < hi; ++i) {
        const double off = std::abs(cand[i] - (a + b) / 2);
        if (cand[i] - a >= options_.min_piece && b - cand[i] >= options_.min_piece && off < best) {
          best = off;
          at = i;
        }
      }
    }
    if (at == hi) continue;
    keep[at] = 1;
    stack.insert(stack.end(), {lo, at, at, hi});
  }
}

// The longest piece: a flat plate's is long (straight runs merge anyway);
// a cylinder's chords may cut inside the circle by at most 0.005 mm at the
// thickest point, r (1 - cos(a / 2)) <= 0.005, as an arc on the base.
double LithophanePlanner::longest_piece() const {
  if (!map_.closed()) return 5.0;
  const double r = map_.base_radius() + map_.max_thickness();
  return 2 * std::acos(1 - 0.005 / r) * map_.base_radius();
}

// How many equal pieces a stretch between two columns needs. A bead has one
// width per piece while its strip's depth changes linearly along it, so at
// a piece's ends two neighbouring beads leave |change of one + change of the
// other| / 4 between them (measured across the band); cut until that is at
// most the edge gap everywhere, but no piece shorter than half a min piece.
int LithophanePlanner::cuts_between(const Column& c0, const Column& c1, double length) const {
  const double dwall = c1.wall - c0.wall;
  double worst = 0;
  if (c0.gap == 0 && c1.gap == 0) {
    worst = std::abs(2 * dwall);  // the two walls meet
  } else {
    // The top pass may take the whole change of the gap (FillGrid), and two
    // passes below it at most that together.
    const double dpass = c1.gap - c0.gap;
    worst = std::max(std::abs(dwall + dpass), std::abs(dpass));
  }
  const double needed = std::ceil(worst / (4 * options_.edge_gap) - 1e-9);
  const double most = std::max(1.0, std::ceil(length / options_.min_piece - 1e-9));  // pieces of at least half a min piece
  return static_cast<int>(std::clamp(needed, 1.0, most));
}

void LithophanePlanner::plan_layer(int index, LithoLayer& out) const {
  if (index < 0 || index >= layers_) throw std::out_of_range("LithophanePlanner::plan_layer: no such layer");
  out.index = index;
  out.z = layer_z(index);
  out.sample_z = (index + 0.5) * options_.layer_height;
  out.paths.clear();
  out.stats = {};
  const double factor = index == 0 ? options_.first_layer_factor : 1.0;
  std::vector<double> s;
  std::vector<Column> cols;
  sample_layer(out.sample_z, s, cols);
  if (!options_.base_wall) widen_base(s, cols);  // a wider base wall would be slower
  const double base_rate = options_.base_wall ? wall_rate_ : fill_rate_;
  if (map_.closed())
    plan_wall_rings(s, cols, wall_rate_ * factor, base_rate * factor, out);
  else
    plan_wall_loop(s, cols, wall_rate_ * factor, base_rate * factor, out);
  plan_fill(s, cols, fill_rate_ * factor, out);
}

// Candidates for the sample points over [first, first + span]: every
// resolution step (`n` of them) and the picture's knots between them.
void LithophanePlanner::sample_candidates(double first, double span, int n, std::vector<double>& cand) const {
  cand.reserve(static_cast<std::size_t>(n) * 2 + 1);
  for (int k = 0; k < n; ++k) {
    const double grid = first + span * k / n;
    const std::size_t at = cand.size();
    map_.knots(grid, first + span * (k + 1) / n, cand);
    // A step's point that close to a knot gives way to the knot (the corner).
    const bool near_knot = (at < cand.size() && cand[at] - grid < options_.min_piece) ||
                           (at > 0 && k > 0 && grid - cand[at - 1] < options_.min_piece);
    if (k == 0 || !near_knot) cand.insert(cand.begin() + static_cast<std::ptrdiff_t>(at), grid);
  }
  if (first + span - cand.back() < options_.min_piece && cand.size() > 1) cand.pop_back();
  cand.push_back(first + span);
}

// The sample points of a layer as they are laid down, one kept point after
// the other: each stretch from the last point cut so that no bead beside
// another leaves a gap; a pass that begins or ends gets its own piece.
struct LithophanePlanner::SampleRun {
  const LithophanePlanner& planner;
  double zs;                  // the height sampled
  double x0;                  // a flat plate's written X at s = 0
  std::vector<double>& s;
  std::vector<Column>& cols;
  double s_prev = 0;
  Column c_prev{};

  // A flat plate's sample points sit on the 0.0001 mm grid of the written X
  // (X = the plate's left end + s), so every piece's extent along the plate
  // is exactly what was planned, however short the piece.
  double snap(double v) const { return planner.map_.closed() ? v : std::round((x0 + v) * 1e4) / 1e4 - x0; }
  Column column(double at) const { return planner.column(at, zs); }
  bool has_pass(double at) const { return column(at).gap > 0; }

  void start(double first) {
    s_prev = snap(first);
    c_prev = column(s_prev);
  }

  void stretch(double end, const Column& c_end, int cuts) {
    s.push_back(s_prev);
    cols.push_back(c_prev);
    for (int j = 1; j < cuts; ++j) {
      const double at = snap(s_prev + (end - s_prev) * j / cuts);
      if (!(at > s.back() && at < end)) continue;
      s.push_back(at);
      cols.push_back(column(at));
    }
    s_prev = end;
    c_prev = c_end;
  }

  void to(double kept) {
    const double s_to = snap(kept);
    if (!(s_to > s_prev)) return;
    const Column c_to = column(s_to);
    if ((c_prev.gap > 0) != (c_to.gap > 0))
      across_switch(s_to, c_to);
    else
      stretch(s_to, c_to, planner.cuts_between(c_prev, c_to, s_to - s_prev));
  }

  // A pass begins or ends between here and s_to: it starts at min pass width
  // while the walls step from sharing the band to one line width each. That
  // step gets a piece of its own, so the beads on either side of it change
  // smoothly and cutting can close their gaps. Across the step the walls
  // change by min pass / 2 and the pass by min pass, plus the thickness's
  // slope x the piece's length: the piece is short enough to keep
  // neighbours within the edge gap (down to 0.001 mm), else min piece.
  void across_switch(double s_to, const Column& c_to) {
    const LithoOptions& o = planner.options_;
    const double slope = std::abs(c_to.t - c_prev.t) / (s_to - s_prev);
    const double room = 4 * o.edge_gap - o.min_pass_width / 2;
    const double jump = room > 0 && slope > 0 ? std::clamp(room / slope, 0.001, 2 * o.min_piece) : 2 * o.min_piece;
    double a = s_prev, b = s_to;  // a on s_prev's side of the switch, b on s_to's
    while (b - a > jump) {
      const double mid = (a + b) / 2;
      (has_pass(mid) == (c_prev.gap > 0) ? a : b) = mid;
    }
    // On the grid, each still on its side of the switch.
    const double unit = planner.map_.closed() ? 0.0 : 1e-4;
    a = snap(a);
    while (a > s_prev && has_pass(a) != (c_prev.gap > 0)) a = std::max(s_prev, a - unit);
    b = snap(b);
    while (b < s_to && has_pass(b) != (c_to.gap > 0)) b = std::min(s_to, b + unit);
    // No sliver of a piece on either side where the step's piece may take it in.
    if (a - s_prev < o.min_piece && b - s_prev <= jump) a = s_prev;
    if (s_to - b < o.min_piece && s_to - a <= jump) b = s_to;
    const Column ca = column(a);
    const Column cb = column(b);
    if (a > s_prev) stretch(a, ca, planner.cuts_between(c_prev, ca, a - s_prev));
    stretch(b, cb, 1);
    if (b < s_to) stretch(s_to, c_to, planner.cuts_between(cb, c_to, s_to - b));
  }

  void finish() {
    s.push_back(s_prev);
    cols.push_back(c_prev);
    if (planner.map_.closed()) cols.back() = cols.front();  // the same column, not a second sample of it
  }
};

// Sample points: the passes' span, from one wall's end to the other's, or the
// whole circle. Candidates: every resolution step and the picture's knots
// between them; kept: those the surface, the longest piece or the pass count need.
void LithophanePlanner::sample_layer(double zs, std::vector<double>& s, std::vector<Column>& cols) const {
  const double lw = options_.line_width;
  const double length = map_.length();
  const double first = map_.closed() ? 0.0 : lw;
  const double span = map_.closed() ? length : length - 2 * lw;
  const int n = std::max(map_.closed() ? 16 : 1, static_cast<int>(std::ceil(span / options_.resolution - 1e-9)));
  s.reserve(static_cast<std::size_t>(n) * 2 + 1);
  cols.reserve(static_cast<std::size_t>(n) * 2 + 1);
  std::vector<double> cand;
  sample_candidates(first, span, n, cand);
  std::vector<char> keep;
  keep_points(cand, zs, keep);
  SampleRun run{*this, zs, point_at(0, 0).x, s, cols, 0, {}};
  run.start(first);
  for (std::size_t k = 1; k < cand.size(); ++k)
    if (keep[k]) run.to(cand[k]);
  run.finish();
}

// The base bead can take a share of the gap like a pass (up to max pass
// width): the counts of passes are chosen as if it could, so where one pass
// fewer would be a little too wide the count stays the same along the layer
// instead of changing, each change a stop of every run beside it and a
// travel (docs/lithophanes.md, Walls and passes).
void LithophanePlanner::widen_base(std::vector<double>& s, std::vector<Column>& cols) const {
  const int m = static_cast<int>(s.size()) - 1;
  const double widest = options_.max_pass_width, slack = std::max(0.0, widest - options_.line_width);
  if (m < 1 || !(slack > 0)) return;
  std::vector<PassRange> ranges(static_cast<std::size_t>(m));
  std::vector<double> lengths(static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k) {
    const double g0 = cols[k].gap, g1 = cols[k + 1].gap;
    const PassRange fewer = pass_range(std::max(0.0, g0 - slack) * (g0 > 0), std::max(0.0, g1 - slack) * (g1 > 0),
                                       options_.min_pass_width, widest);
    const PassRange plain = pass_range(g0, g1, options_.min_pass_width, widest);
    // A flat plate's end caps meet the base bead at its own width.
    const bool end = !map_.closed() && (k == 0 || k == m - 1);
    ranges[k] = {end ? plain.fewest : std::min(fewer.fewest, plain.fewest), plain.most};
    lengths[k] = s[k + 1] - s[k];
  }
  const std::vector<int> passes = steady_pass_counts(ranges, lengths);
  // How much wider the base bead must be (lo) and may be (hi) at each point
  // for the counts chosen; it takes the taut string through that corridor,
  // so it bends only where it must, like the passes below the top one.
  const std::size_t n = cols.size();
  std::vector<double> lo(n, 0.0), hi(n, slack), x(s.begin(), s.end());
  for (int k = 0; k < m; ++k) {
    const int c = passes[static_cast<std::size_t>(k)];
    for (int i : {k, k + 1}) {
      if (c < 1 || !(cols[i].gap > 0)) {
        hi[i] = 0;
        continue;
      }
      lo[i] = std::max(lo[i], cols[i].gap - c * widest);
      hi[i] = std::min(hi[i], cols[i].gap - c * options_.min_pass_width);
    }
  }
  if (!map_.closed()) hi.front() = hi.back() = 0;
  for (std::size_t i = 0; i < n; ++i) {
    hi[i] = std::max(0.0, hi[i]);
    lo[i] = std::clamp(lo[i], 0.0, hi[i]);
  }
  const double end = map_.closed() ? std::max(lo.front(), lo.back()) : 0.0;
  std::vector<double> extra = taut_string(x, lo, hi, end, end);
  for (std::size_t i = 0; i < n; ++i) extra[i] = std::clamp(extra[i], lo[i], hi[i]);
  apply_base_extra(extra, s, cols);
}

// Where the base bead widens along a piece, the beads on both sides of its
// edge change width the more: the piece is cut further, so that neighbours
// again leave at most the edge gap (cuts_between).
void LithophanePlanner::apply_base_extra(const std::vector<double>& extra, std::vector<double>& s,
                                         std::vector<Column>& cols) const {
  const int m = static_cast<int>(s.size()) - 1;
  std::vector<int> cuts(static_cast<std::size_t>(m), 1);
  for (int k = 0; k < m; ++k) {
    const double de = std::abs(extra[k + 1] - extra[k]);
    if (!(de > 0)) continue;
    const double worst = de + std::abs(cols[k + 1].gap - cols[k].gap) + std::abs(cols[k + 1].wall - cols[k].wall);
    const double needed = std::ceil(worst / (4 * options_.edge_gap) - 1e-9);
    // A piece too short to cut that often (a steep edge): the layer keeps its changes of count.
    if (needed > std::max(1.0, std::floor((s[k + 1] - s[k]) / options_.min_piece))) return;
    cuts[static_cast<std::size_t>(k)] = static_cast<int>(needed);
  }
  const double unit = map_.closed() ? 0.0 : 1e-4;
  const double x0 = point_at(0, 0).x;
  auto snap = [&](double v) { return unit > 0 ? std::round((x0 + v) * 1e4) / 1e4 - x0 : v; };
  std::vector<double> s2;
  std::vector<Column> cols2;
  s2.reserve(s.size());
  cols2.reserve(cols.size());
  for (int k = 0; k <= m; ++k) {
    Column c = cols[k];
    c.extra = extra[k];
    c.gap -= extra[k];
    s2.push_back(s[k]);
    cols2.push_back(c);
    if (k == m) break;
    const int parts = cuts[static_cast<std::size_t>(k)];
    for (int j = 1; j < parts; ++j) {
      const double at = snap(s[k] + (s[k + 1] - s[k]) * j / parts);
      if (!(at > s2.back() && at < s[k + 1])) continue;
      const double f = (at - s[k]) / (s[k + 1] - s[k]);
      // The piece's boundaries are linear between its ends: so are the new points'.
      auto lerp = [f](double a, double b) { return a + (b - a) * f; };
      Column mid{lerp(cols[k].t, cols[k + 1].t), lerp(cols[k].wall, cols[k + 1].wall),
                 lerp(cols[k].gap, cols[k + 1].gap), lerp(extra[k], extra[k + 1])};
      mid.gap -= mid.extra;
      s2.push_back(at);
      cols2.push_back(mid);
    }
  }
  s.swap(s2);
  cols.swap(cols2);
}

LithophanePlanner::Strip LithophanePlanner::wall_strip(double s0, const Column& c0, double s1, const Column& c1,
                                                       bool outer) {
  return outer ? Strip{s0, c0.t - c0.wall, c0.t, s1, c1.t - c1.wall, c1.t}
               : Strip{s0, 0, c0.wall + c0.extra, s1, 0, c1.wall + c1.extra};
}

PathRole LithophanePlanner::base_role() const { return options_.base_wall ? PathRole::WallInner : PathRole::Base; }

// A cylinder's walls: the outer ring, then the inner (base) ring, as the
// paper prints them; both start at s = 0.
void LithophanePlanner::plan_wall_rings(const std::vector<double>& s, const std::vector<Column>& cols, double rate,
                                        double base_rate, LithoLayer& out) const {
  for (bool outer : {true, false}) {
    Path path;
    path.role = outer ? PathRole::WallOuter : base_role();
    const double r = outer ? rate : base_rate;
    const double mid0 = outer ? cols[0].t - cols[0].wall / 2 : (cols[0].wall + cols[0].extra) / 2;
    path.start = point_at(0, mid0);
    for (std::size_t k = 0; k + 1 < s.size(); ++k)
      add_strip(wall_strip(s[k], cols[k], s[k + 1], cols[k + 1], outer), r, path, out.stats);
    if (!path.pieces.empty()) path.pieces.back().to = path.start;  // close the ring exactly
    out.paths.push_back(std::move(path));
  }
}

// A flat plate's walls, one loop: the base bead (or inner wall) left to
// right along the base, a cap across the right end, the outer wall back
// along the picture, a cap across the left end.
void LithophanePlanner::plan_wall_loop(const std::vector<double>& s, const std::vector<Column>& cols, double rate,
                                       double base_rate, LithoLayer& out) const {
  const double lw = options_.line_width;
  const double zs = out.sample_z;
  const double left = lw / 2;
  const double right = map_.length() - lw / 2;
  const Column cl = column(left, zs);
  const Column cr = column(right, zs);
  Path inner;
  inner.role = base_role();
  inner.start = point_at(left, cl.wall / 2);
  add_strip(wall_strip(left, cl, s[0], cols[0], false), base_rate, inner, out.stats);
  const std::size_t last = s.size() - 1;
  for (std::size_t k = 0; k < last; ++k)
    add_strip(wall_strip(s[k], cols[k], s[k + 1], cols[k + 1], false), base_rate, inner, out.stats);
  add_strip(wall_strip(s[last], cols[last], right, cr, false), base_rate, inner, out.stats);
  Path outer;
  outer.role = PathRole::WallOuter;
  outer.start = end_of(inner);
  add_cap(outer.start, point_at(right, cr.t - cr.wall / 2), rate, outer, out.stats);
  add_strip(wall_strip(right, cr, s[last], cols[last], true), rate, outer, out.stats);
  for (std::size_t k = last; k > 0; --k)
    add_strip(wall_strip(s[k], cols[k], s[k - 1], cols[k - 1], true), rate, outer, out.stats);
  add_strip(wall_strip(s[0], cols[0], left, cl, true), rate, outer, out.stats);
  add_cap(end_of(outer), inner.start, rate, outer, out.stats);
  out.paths.push_back(std::move(inner));
  out.paths.push_back(std::move(outer));
}

// Where the passes lie: vertex i (sample point i; on a cylinder it may go
// past the seam: index modulo m, s unwrapped) and the depths of pass j of
// `count` side by side there. Only the top pass (beside the outer wall) has
// to follow the picture. The passes below it share one width along their
// run, bent only where the top pass would leave [min pass width, max pass
// width], and then as little as possible (the taut string through what the
// top pass allows): they run straight where the picture changes every
// pixel instead of turning, and the head with them, at every change.
struct LithophanePlanner::FillGrid {
  const std::vector<double>& s;
  const std::vector<Column>& cols;
  int m;        // pieces
  bool cyclic;  // a cylinder
  double length;
  double min_width;
  double max_width;
  double edge_gap;
  int first = 0;              // the run being planned: its first vertex
  std::vector<double> lower;  // and the width of each pass below the top one, per vertex from `first`
  std::vector<int> splits;    // and into how many equal pieces each of its pieces is cut

  double s_of(int i) const {
    return cyclic ? s[static_cast<std::size_t>(i % m)] + (i / m) * length : s[static_cast<std::size_t>(i)];
  }
  const Column& col_of(int i) const { return cols[static_cast<std::size_t>(cyclic ? i % m : i)]; }
  void depth(int i, int j, int count, double& a, double& b) const {
    const Column& c = col_of(i);
    const double w = count > 1 ? lower[static_cast<std::size_t>(i - first)] : c.gap;
    const double base = c.wall + c.extra;
    a = base + w * j;
    b = j + 1 < count ? base + w * (j + 1) : base + c.gap;
  }
  // The widths below the top pass over the run of vertices k..end with `count` passes.
  void plan_run(int k, int end, int count) {
    first = k;
    lower.clear();
    splits.clear();
    if (count < 2) return;
    const std::size_t n = static_cast<std::size_t>(end - k + 1);
    std::vector<double> x(n), lo(n), hi(n);
    double mean = 0;
    for (std::size_t v = 0; v < n; ++v) {
      const int i = k + static_cast<int>(v);
      const double gap = col_of(i).gap;
      x[v] = s_of(i);
      lo[v] = std::max(min_width, (gap - max_width) / (count - 1));
      hi[v] = std::min(max_width, (gap - min_width) / (count - 1));
      if (!(lo[v] <= hi[v])) lo[v] = hi[v] = gap / count;  // a pass begins or ends here: equal shares
      mean += gap / count / static_cast<double>(n);
    }
    const double floor = *std::max_element(lo.begin(), lo.end());
    const double ceiling = *std::min_element(hi.begin(), hi.end());
    if (floor <= ceiling)  // one width fits the whole run: straight from end to end
      lower.assign(n, std::clamp(mean, floor, ceiling));
    else
      lower = taut_string(x, lo, hi, std::clamp(mean, lo.front(), hi.front()), std::clamp(mean, lo.back(), hi.back()));
    plan_splits(k, count);
  }
  // Where the passes below the top one bend, the passes change width along
  // pieces the sampling cut for equal shares: such a piece is cut further
  // until neighbouring beads (walls included) again leave at most the edge
  // gap, |change of one + change of the other| / 4 (docs/lithophanes.md).
  void plan_splits(int k, int count) {
    splits.assign(lower.size() > 0 ? lower.size() - 1 : 0, 1);
    for (std::size_t v = 0; v < splits.size(); ++v) {
      const Column& c0 = col_of(k + static_cast<int>(v));
      const Column& c1 = col_of(k + static_cast<int>(v) + 1);
      const double dwall = c1.wall - c0.wall;
      const double dbase = dwall + c1.extra - c0.extra;
      const double dlow = lower[v + 1] - lower[v];
      const double dtop = (c1.gap - c0.gap) - (count - 1) * dlow;
      double worst = std::max(std::abs(dbase + dlow), std::abs(dtop + dwall));
      worst = std::max(worst, std::abs(dlow + (count > 2 ? dlow : dtop)));
      worst = std::max(worst, std::abs(dlow + dtop));
      splits[v] = std::max(1, static_cast<int>(std::ceil(worst / (4 * edge_gap) - 1e-9)));
    }
  }
  int split_of(int i0, int i1) const {
    const int v = std::min(i0, i1) - first;
    return v >= 0 && static_cast<std::size_t>(v) < splits.size() ? splits[static_cast<std::size_t>(v)] : 1;
  }
};

// The passes between the walls. Piece k (from s[k] to s[k+1]) carries equal
// passes, each within [min pass width, max pass width] at both its ends, as
// many as keep the count steady along the layer (pass_counts.hpp);
// consecutive pieces with the same count form a group printed as that many
// runs side by side. Where the count changes, the runs end and new ones begin.
void LithophanePlanner::plan_fill(const std::vector<double>& s, const std::vector<Column>& cols, double rate,
                                  LithoLayer& out) const {
  const int m = static_cast<int>(s.size()) - 1;  // pieces
  const bool cyclic = map_.closed();
  std::vector<PassRange> ranges(static_cast<std::size_t>(m));
  std::vector<double> lengths(static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k) {
    ranges[k] = pass_range(cols[k].gap, cols[k + 1].gap, options_.min_pass_width, options_.max_pass_width);
    lengths[k] = s[k + 1] - s[k];
  }
  const std::vector<int> passes = steady_pass_counts(ranges, lengths);
  for (int p : passes) out.stats.max_passes = std::max(out.stats.max_passes, p);
  FillGrid grid{s, cols, m, cyclic, map_.length(), options_.min_pass_width, options_.max_pass_width, options_.edge_gap, 0, {}, {}};
  Point cur = out.paths.empty() ? Point{} : end_of(out.paths.back());
  const bool ring = cyclic && std::all_of(passes.begin(), passes.end(), [&](int p) { return p == passes[0]; });
  if (ring) {
    grid.plan_run(0, m, passes[0]);
    plan_fill_rings(grid, passes[0], rate, out);
    return;
  }
  int start = 0;
  if (cyclic)
    while (passes[static_cast<std::size_t>((start + m - 1) % m)] == passes[static_cast<std::size_t>(start)]) ++start;
  int k = start;
  while (k < start + m) {
    const int count = passes[static_cast<std::size_t>(k % m)];
    int end = k;
    while (end < start + m && passes[static_cast<std::size_t>(end % m)] == count) ++end;
    if (count > 0) {
      grid.plan_run(k, end, count);
      cur = plan_fill_group(grid, k, end, count, cur, rate, out);
    }
    k = end;
  }
}

// A cylinder with the same count of passes all round: each pass a closed ring from s = 0.
void LithophanePlanner::plan_fill_rings(const FillGrid& grid, int count, double rate, LithoLayer& out) const {
  for (int j = 0; j < count; ++j) {
    Path path;
    path.role = PathRole::Fill;
    double a = 0, b = 0;
    grid.depth(0, j, count, a, b);
    path.start = point_at(0, (a + b) / 2);
    for (int k = 0; k < grid.m; ++k) {
      double a1 = 0, b1 = 0;
      grid.depth(k + 1, j, count, a1, b1);
      add_fill_strip({grid.s_of(k), a, b, grid.s_of(k + 1), a1, b1}, grid.split_of(k, k + 1), rate, path, out.stats);
      a = a1;
      b = b1;
    }
    if (!path.pieces.empty()) path.pieces.back().to = path.start;
    out.paths.push_back(std::move(path));
  }
}

// The `count` runs side by side over vertices k..end: from the corner nearest
// the head (at `cur`), then serpentine. Returns where the head ends.
Point LithophanePlanner::plan_fill_group(const FillGrid& grid, int k, int end, int count, Point cur, double rate,
                                         LithoLayer& out) const {
  double best = 0;
  bool from_low = true, forward = true;
  for (bool low : {true, false})
    for (bool fwd : {true, false}) {
      double a = 0, b = 0;
      grid.depth(fwd ? k : end, low ? 0 : count - 1, count, a, b);
      const double d = distance(cur, point_at(grid.s_of(fwd ? k : end), (a + b) / 2));
      if ((low && fwd) || d < best) {
        best = d;
        from_low = low;
        forward = fwd;
      }
    }
  for (int p = 0; p < count; ++p) {
    const int j = from_low ? p : count - 1 - p;
    const bool fwd = forward == (p % 2 == 0);
    Path path;
    path.role = PathRole::Fill;
    int i = fwd ? k : end;
    const int step = fwd ? 1 : -1;
    double a = 0, b = 0;
    grid.depth(i, j, count, a, b);
    path.start = point_at(grid.s_of(i), (a + b) / 2);
    for (; fwd ? i < end : i > k; i += step) {
      double a1 = 0, b1 = 0;
      grid.depth(i + step, j, count, a1, b1);
      add_fill_strip({grid.s_of(i), a, b, grid.s_of(i + step), a1, b1}, grid.split_of(i, i + step), rate, path,
                     out.stats);
      a = a1;
      b = b1;
    }
    cur = end_of(path);
    out.paths.push_back(std::move(path));
  }
  return cur;
}

}  // namespace gcode::litho
