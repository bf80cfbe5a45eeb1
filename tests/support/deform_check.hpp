#pragma once
// The independent checker of gc-deform (it shares none of its code: the
// formula is a C++ function here, not muparser; the cutting, the E and the
// checks are computed again from the G-code as MachineState replays it):
//   (a) every output move of the layers, sampled every 0.05 mm, lies within
//       the tolerance of the image of the input path (the input's moves of
//       the same layer sampled every 0.05 mm, through the formula);
//   (b) back: every sample of the image of an input extrusion lies within
//       the tolerance of an output extrusion (nothing left out);
//   (c) every output extrusion piece has E = the input move's filament per
//       mm x the cross-section factor at its pre-image x its length, to E's
//       rounding, and lies on the image of an input extrusion;
//   (d) the total filament of the layers against the integral of the
//       deformed bead volume along the image (filament per mm x factor x
//       length of the image), to 1 %.
#include <array>
#include <cstddef>
#include <functional>
#include <string>

namespace deformtest {

using P3 = std::array<double, 3>;
using Map = std::function<P3(const P3&)>;
using Factor = std::function<double(const P3&)>;

// dFZ/dz by a central difference of 0.0005 mm (gc-deform's own differs).
inline Factor layer_factor(Map map) {
  return [map](const P3& p) {
    const double h = 0.0005;
    return (map({p[0], p[1], p[2] + h})[2] - map({p[0], p[1], p[2] - h})[2]) / (2 * h);
  };
}

struct DeformCheck {
  double worst_out = 0;    // (a) mm
  std::size_t worst_out_line = 0;  // (a) where (0-based line of the output)
  double worst_back = 0;   // (b) mm
  double worst_e = -1;     // (c) mm of filament beyond the allowance (<= 0 holds)
  std::size_t off_extrusion = 0;  // (c) output extrusions whose nearest image is a travel
  double filament_out = 0, filament_expected = 0;  // (d)
  std::size_t output_pieces = 0;
  std::size_t entry_travels = 0;  // travel that starts off the image: into the deformed layers from the start code
};

// Checks gc-deform's `output` of `input` against the deformation `map` and
// the bead's cross-section factor `section` (deform_check.cpp).
DeformCheck check_deform(const std::string& input, const std::string& output, const Map& map, const Factor& section,
                         double tolerance);

}  // namespace deformtest
