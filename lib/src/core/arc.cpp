#include "gcode/core/arc.hpp"

#include <cmath>

namespace gcode {

Arc make_arc(double x0, double y0, double x1, double y1, bool clockwise, bool has_ij, double i, double j,
             double r) {
  constexpr double kTwoPi = 6.283185307179586;
  Arc a;
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
  if (clockwise) {
    if (sweep >= 0) sweep -= kTwoPi;
  } else {
    if (sweep <= 0) sweep += kTwoPi;
  }
  // Start and end on the same point: a full circle, not a zero arc.
  a.sweep = sweep;
  a.valid = true;
  return a;
}

}  // namespace gcode
