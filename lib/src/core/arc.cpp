#include "gcode/core/arc.hpp"

#include <cmath>

namespace gcode {

namespace {
constexpr double kTwoPi = 6.283185307179586;
}  // namespace

double Arc::length(double dz) const { return std::hypot(length_xy(), dz); }

Arc make_arc(double x0, double y0, double x1, double y1, bool clockwise, bool has_ij, double i, double j,
             double r, int extra_turns) {
  Arc a;
  if (extra_turns < 0 || extra_turns > kMaxArcTurns) return a;
  if (has_ij) {
    a.cx = x0 + i;
    a.cy = y0 + j;
  } else {
    // Centre from the chord and the radius: the perpendicular bisector.
    double dx = x1 - x0, dy = y1 - y0;
    double chord = std::hypot(dx, dy);
    if (chord == 0 || r == 0 || !std::isfinite(r)) return a;
    double rr = std::fabs(r);
    double h2 = rr * rr - chord * chord / 4;
    double h = h2 > 0 ? std::sqrt(h2) : 0;  // tolerate a radius slightly too small
    // Marlin: for the short arc the centre lies to the right of a CW chord.
    double sign = (clockwise ? -1.0 : 1.0) * (r < 0 ? -1.0 : 1.0);
    double mx = x0 + dx / 2, my = y0 + dy / 2;
    a.cx = mx - sign * h * dy / chord;
    a.cy = my + sign * h * dx / chord;
  }
  a.radius = std::hypot(x0 - a.cx, y0 - a.cy);
  if (!(a.radius > 0) || !std::isfinite(a.radius)) return a;
  a.start_angle = std::atan2(y0 - a.cy, x0 - a.cx);
  double end_angle = std::atan2(y1 - a.cy, x1 - a.cx);
  double sweep = end_angle - a.start_angle;
  // Start and end on the same point: a full circle, not a zero arc.
  if (clockwise) {
    if (sweep >= 0) sweep -= kTwoPi;
  } else {
    if (sweep <= 0) sweep += kTwoPi;
  }
  a.sweep = sweep + (clockwise ? -kTwoPi : kTwoPi) * extra_turns;
  a.extra_turns = extra_turns;
  a.valid = true;
  return a;
}

Arc make_arc(const Line& line, double x0, double y0, double x1, double y1, double scale) {
  int turns = 0;
  if (const Word* p = line.find('P'); p != nullptr && p->has_value) {
    // Marlin reads P as a whole number; a fraction or a sign means the line is not what it seems.
    if (!(p->value() >= 0 && p->value() <= kMaxArcTurns) || p->value() != std::floor(p->value())) return Arc{};
    turns = static_cast<int>(p->value());
  }
  bool has_ij = line.has('I') || line.has('J');
  return make_arc(x0, y0, x1, y1, line.number == 2, has_ij, line.value_or('I', 0) * scale,
                  line.value_or('J', 0) * scale, line.value_or('R', 0) * scale, turns);
}

}  // namespace gcode
