#pragma once
// Geometry of G2/G3 arcs in the XY plane (G17), in the I/J (centre offset)
// and R (radius) forms, with helical Z.
#include "gcode/core/machine_state.hpp"

namespace gcode {

struct Arc {
  double cx = 0, cy = 0;   // centre
  double radius = 0;
  double start_angle = 0;  // radians
  double sweep = 0;        // signed: positive counter-clockwise (G3), negative clockwise (G2)
  bool valid = false;      // false when the words do not describe an arc

  double length_xy() const { return radius * (sweep < 0 ? -sweep : sweep); }
};

// The arc from (x0,y0) to (x1,y1). `clockwise` for G2. For the I/J form pass
// has_ij with the offsets; otherwise `r` (negative R = the long way round).
// Equal start and end with I/J is a full circle.
Arc make_arc(double x0, double y0, double x1, double y1, bool clockwise, bool has_ij, double i, double j,
             double r);

}  // namespace gcode
