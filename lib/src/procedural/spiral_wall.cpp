#include "gcode/procedural/spiral_wall.hpp"

#include <algorithm>
#include <cmath>

namespace gcode::procedural {

namespace {

constexpr double kInside = 1e-4;  // mm: how far inside the model a section stays
constexpr double kMinStep = 2e-3;  // mm: twice the unit X and Y are written in

// A closed loop measured along its length: positions and points there.
class LoopWalk {
 public:
  explicit LoopWalk(const Polygon& loop) : loop_(loop), at_(loop.size() + 1, 0) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Point2& a = loop[i];
      const Point2& b = loop[(i + 1) % loop.size()];
      at_[i + 1] = at_[i] + distance(a, b);
    }
  }
  double length() const { return at_.back(); }

  // The position (0 .. length) of the loop's point nearest p.
  double nearest(const Point2& p) const {
    double best = 1e300, where = 0;
    for (std::size_t i = 0; i < loop_.size(); ++i) {
      const Point2& a = loop_[i];
      const Point2& b = loop_[(i + 1) % loop_.size()];
      const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
      const double t = l2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / l2, 0.0, 1.0) : 0;
      const double ex = p.x - a.x - t * dx, ey = p.y - a.y - t * dy, d = ex * ex + ey * ey;  // squared
      if (d < best) best = d, where = at_[i] + t * (at_[i + 1] - at_[i]);
    }
    return where;
  }

  Point2 point_at(double s) const {
    const double m = std::fmod(std::fmod(s, length()) + length(), length());
    const std::size_t i = std::min<std::size_t>(
        loop_.size() - 1, static_cast<std::size_t>(std::upper_bound(at_.begin(), at_.end(), m) - at_.begin()) - 1);
    const double span = at_[i + 1] - at_[i];
    const double t = span > 0 ? (m - at_[i]) / span : 0;
    const Point2& a = loop_[i];
    const Point2& b = loop_[(i + 1) % loop_.size()];
    return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t};
  }

  // Calls visit(position, point) for the point at `from`, every corner
  // after it before `to`, and the point at `to` (positions unwrapped: from
  // <= position <= to, to - from at most one length).
  template <typename Visit>
  void walk(double from, double to, Visit visit) const {
    visit(from, point_at(from));
    const double len = length();
    double base = std::floor(from / len) * len;
    std::size_t i = static_cast<std::size_t>(std::upper_bound(at_.begin(), at_.end(), from - base) - at_.begin());
    while (true) {
      if (i > loop_.size()) i = 1, base += len;
      const double s = base + at_[i];
      if (s >= to) break;
      visit(s, loop_[i % loop_.size()]);
      ++i;
    }
    visit(to, point_at(to));
  }

 private:
  const Polygon& loop_;
  std::vector<double> at_;  // position of each corner; the last is the length (back at corner 0)
};

int pieces_for(double lean, const SpiralWallOptions& o) {
  return std::clamp(static_cast<int>(std::ceil(lean * o.pitch / (2 * o.tolerance))), 1, kMaxPieces);
}

}  // namespace

double section_height(double z, double model_top) { return std::clamp(z, kInside, model_top - kInside); }

void spiral_wall(MeshSlicer& slicer, const SpiralWallOptions& o, Point2 from, std::vector<ShapeLayer>& out,
                 HeightProblems& problems) {
  for (int k = 0; k < o.turns; ++k) {
    const double z0 = o.base + k * o.pitch;
    slicer.band(section_height(z0 - o.pitch / 2, o.model_top), section_height(z0 + o.pitch / 2, o.model_top));
    const int pieces = pieces_for(slicer.band_lean(), o);
    ShapeLayer layer;
    layer.start_bead = k == 0 ? 0 : -1;
    for (int j = 0; j < pieces; ++j) {
      const double cut = section_height(z0 + (j + 0.5) / pieces * o.pitch - o.pitch / 2, o.model_top);
      const WallOutline outline = wall_outline(slicer.section(cut), o.line_width, o.tolerance);
      if (!outline.problem.empty()) {
        problems.add(outline.problem, cut);
        continue;
      }
      const LoopWalk walk(outline.line);
      const double s0 = walk.nearest(from), len = walk.length();
      walk.walk(s0 + len * j / pieces, s0 + len * (j + 1) / pieces, [&](double s, const Point2& p) {
        // One expression for every Z, and the piece's ends exactly its fractions, so that where one
        // piece or turn ends and the next begins the Z is the same number (not one rounding step apart).
        const double f = std::clamp((s - s0) / len, static_cast<double>(j) / pieces, static_cast<double>(j + 1) / pieces);
        const double z = o.base + (k + f) * o.pitch;
        const PathPoint point{p.x, p.y, z, std::min(z - o.base, o.pitch)};
        // Two points closer than X and Y are written would make a move of Z alone: the later one stands for both.
        if (!layer.points.empty() && distance_squared(p, {layer.points.back().x, layer.points.back().y}) < kMinStep * kMinStep)
          layer.points.back() = point;
        else
          layer.points.push_back(point);
      });
    }
    if (!layer.points.empty()) from = {layer.points.back().x, layer.points.back().y};
    out.push_back(std::move(layer));
  }
}

}  // namespace gcode::procedural
