#pragma once
// The independent checker of gc-shape's output: the G-code replayed through
// MachineState and measured against each primitive's curve as the man page
// defines it (not the library's points):
//   (a) every extruding piece in the layers, sampled every 0.05 mm, lies
//       within the tolerance of its curve (radius and height at its angle),
//   (b) its filament is width x the bead height (min(z - base, pitch)) x its
//       length / filament area, to E's rounding,
//   (c) inside the layers nothing but extrusion: no travel, no Z-only move,
//       no retraction (a rising spiral has no layer change).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/procedural/shape.hpp"
#include "test_support.hpp"

namespace shapetest {

using gcode::procedural::ShapeKind;
using gcode::procedural::ShapeOptions;

struct ShapeCheck {
  std::size_t pieces = 0;
  double worst_chord = 0;   // mm, largest distance of a sample from the curve
  double worst_e = -1;       // mm of filament, largest |E - the bead's| beyond E's and Z's rounding (<= 0: holds)
  double filament = 0;      // mm, in the layers
  std::size_t other_moves = 0;  // travel, Z-only moves or retractions in the layers
};

// The curve at unwrapped angle `phi` (radians from the path's start angle):
// radius and height, from the documented geometry.
struct Curve {
  ShapeOptions o;
  double pitch = 0;  // of the rising wall
  int turns = 0;
  double base = 0;   // Z the wall stands on
  double radius(double phi, bool bottom) const {
    const double turn = 2 * std::numbers::pi;
    if (o.kind == ShapeKind::Spiral) return o.diameter / 2 - o.line_width * phi / turn;
    if (bottom) return o.line_width / 2 + o.line_width * phi / turn;
    if (o.kind == ShapeKind::Cone) return (o.diameter + (o.top_diameter - o.diameter) * phi / (turn * turns)) / 2;
    return o.diameter / 2;
  }
  double z(double phi, bool bottom) const {
    if (bottom || o.kind == ShapeKind::Circle || o.kind == ShapeKind::Spiral) return o.layer_height;
    return base + pitch * phi / (2 * std::numbers::pi);
  }
  double bead(double z_at, bool bottom) const {
    if (bottom || o.kind == ShapeKind::Circle || o.kind == ShapeKind::Spiral) return o.layer_height;
    return std::min(z_at - base, pitch);
  }
};

// Distance of (x, y) from a polygon's edge through the corners on the radius.
inline double polygon_distance(const ShapeOptions& o, double x, double y) {
  const double a = std::atan2(y - o.center_y, x - o.center_x);
  const double side = 2 * std::numbers::pi / o.sides;
  const double k = std::floor((a < 0 ? a + 2 * std::numbers::pi : a) / side);
  const double r = o.diameter / 2;
  const double ax = o.center_x + r * std::cos(k * side), ay = o.center_y + r * std::sin(k * side);
  const double bx = o.center_x + r * std::cos((k + 1) * side), by = o.center_y + r * std::sin((k + 1) * side);
  const double ex = bx - ax, ey = by - ay;
  return std::fabs((x - ax) * ey - (y - ay) * ex) / std::hypot(ex, ey);
}

// The angle of (x, y) about the centre, unwrapped along the path.
class Unwrap {
 public:
  Unwrap(double cx, double cy) : cx_(cx), cy_(cy) {}
  void restart(double x, double y) {
    last_ = std::atan2(y - cy_, x - cx_);
    total_ = 0;
  }
  // The unwrapped angle at (x, y); `keep`: the new point becomes the reference.
  double at(double x, double y, bool keep) {
    const double a = std::atan2(y - cy_, x - cx_);
    double d = a - last_;
    while (d > std::numbers::pi) d -= 2 * std::numbers::pi;
    while (d < -std::numbers::pi) d += 2 * std::numbers::pi;
    if (keep) last_ = a, total_ += d;
    return std::fabs(keep ? total_ : total_ + d);
  }

 private:
  double cx_, cy_, last_ = 0, total_ = 0;
};

inline ShapeCheck check_shape(const std::string& text, const ShapeOptions& o, double pitch, int turns) {
  ShapeCheck c;
  const Curve curve{o, pitch, turns, o.kind == ShapeKind::Cylinder ? o.layer_height : 0};
  const double area = std::numbers::pi * 1.75 * 1.75 / 4;
  const gctest::LinePlace places = gctest::places_of(text);
  Unwrap angle(o.center_x, o.center_y);
  bool was_bottom = false, started = false;
  for (const gctest::ReplayedMove& m : gctest::replay_moves(text)) {
    const int layer = places.layer[m.line_index];
    if (layer == 0) continue;
    if (!m.move.extruding || m.move.filament <= 0) {
      ++c.other_moves;
      continue;
    }
    const bool bottom = o.kind == ShapeKind::Cylinder && layer == 1;
    if (!started || bottom != was_bottom) angle.restart(m.move.start[0], m.move.start[1]);  // the wall counts from its start
    started = true, was_bottom = bottom;
    ++c.pieces;
    const int samples = std::max(2, static_cast<int>(std::ceil(m.move.length / 0.05)));
    for (int s = 1; s <= samples; ++s) {
      const double t = static_cast<double>(s) / samples;
      double p[3];
      for (int a = 0; a < 3; ++a) p[a] = m.move.start[a] + (m.move.end[a] - m.move.start[a]) * t;
      const double phi = angle.at(p[0], p[1], s == samples);
      double off = 0;
      if (o.kind == ShapeKind::Polygon) {
        off = polygon_distance(o, p[0], p[1]);  // Z rises along the edges, not with the angle
      } else {
        off = std::max(std::fabs(std::hypot(p[0] - o.center_x, p[1] - o.center_y) - curve.radius(phi, bottom)),
                       std::fabs(p[2] - curve.z(phi, bottom)));
      }
      c.worst_chord = std::max(c.worst_chord, off);
    }
    const double bead = (curve.bead(m.move.start[2], bottom) + curve.bead(m.move.end[2], bottom)) / 2;
    const double want = o.line_width * bead * m.move.length / area;
    // E is rounded to 1e-5 with a carry; the bead height on the ramp is read from Z's 3 decimals.
    const double rounding = 1.01e-5 + o.line_width * 0.0005 * m.move.length / area;
    c.worst_e = std::max(c.worst_e, std::fabs(m.move.filament - want) - rounding);
    c.filament += m.move.filament;
  }
  return c;
}

}  // namespace shapetest
