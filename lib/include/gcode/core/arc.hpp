#pragma once
// Geometry of G2/G3 arcs in the XY plane (G17), in the I/J (centre offset)
// and R (radius) forms, with helical Z and Marlin's P word (ARC_P_CIRCLES:
// P full turns before the arc itself).
#include "gcode/core/line.hpp"

namespace gcode {

// Marlin refuses a P outside 0..100 (STR_ERR_ARC_ARGS).
inline constexpr int kMaxArcTurns = 100;

struct Arc {
  double cx = 0, cy = 0;   // centre
  double radius = 0;
  double start_angle = 0;  // radians
  double sweep = 0;        // signed, extra turns included: positive counter-clockwise (G3), negative clockwise (G2)
  int extra_turns = 0;     // the P word: full turns in `sweep` besides the arc to the end point
  bool valid = false;      // false when the words do not describe an arc

  double length_xy() const { return radius * (sweep < 0 ? -sweep : sweep); }
  // The path length with `dz` of helical rise shared out along the sweep, as
  // Marlin does (each turn takes its share of Z and E by angle).
  double length(double dz) const;
};

// The arc from (x0,y0) to (x1,y1). `clockwise` for G2. For the I/J form pass
// has_ij with the offsets; otherwise `r` (negative R = the long way round).
// Equal start and end with I/J is a full circle. `extra_turns` (P) adds full
// turns in the arc's direction; outside 0..kMaxArcTurns the arc is invalid.
Arc make_arc(double x0, double y0, double x1, double y1, bool clockwise, bool has_ij, double i, double j,
             double r, int extra_turns = 0);

// The arc a G2/G3 line describes from (x0,y0) to (x1,y1), in mm: its I and J
// (or R) times `scale` (25.4 after G20), and P as extra turns. A P that is not
// a whole number from 0 to kMaxArcTurns makes the arc invalid.
//
// Firmwares differ on P: Marlin with ARC_P_CIRCLES turns P full circles and
// then the arc (a P1 arc back to its start point is two turns); Marlin without
// it ignores P; BambuStudio's estimator counts "G3 Z.6 I1.217 J0 P1" (start =
// end) as one turn of P. This follows Marlin's ARC_P_CIRCLES.
Arc make_arc(const Line& line, double x0, double y0, double x1, double y1, double scale = 1);

}  // namespace gcode
