#pragma once
// Rewrites a stream's lines for a splice: Z shifted, E in the output's mode
// and coordinate (exact decimals, the input's precision), extrusion scaled.
#include <string>
#include <string_view>

#include "gcode/core/fixed.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line_builder.hpp"

namespace gcode {

// Rewrites a stream's lines for a splice: Z shifted, E in the output's mode
// and coordinate, extrusion scaled. Lines that need none of it stay as they
// are (apply returns false).
class SpliceRewrite {
 public:
  // `relative_e`, `e`: the output's E mode and coordinate where the lines start.
  void reset(Fixed z_shift, double extrusion_scale, bool relative_e, Fixed e);
  // `precision`: the decimals to write at least (the output's).
  bool apply(const TrackedLine& t, const Precision& precision, std::string_view& text);
  bool identity() const { return identity_; }
  bool relative_e() const { return relative_e_; }
  Fixed e() const { return e_; }
  Fixed z_shift() const { return shift_; }
  double scale() const { return scale_; }

 private:
  Fixed scaled(Fixed amount, int decimals);
  Fixed shift_;
  double scale_ = 1;
  bool identity_ = true;
  bool relative_e_ = false;
  Fixed e_;
  Fixed source_pushed_;  // extruded by the source since reset (scaled moves)
  Fixed output_pushed_;  // written for them, rounded, the rounding carried
  std::string text_;
};

}  // namespace gcode
