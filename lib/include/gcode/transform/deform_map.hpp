#pragma once
// The formulas of gc-deform (background.md §2, draw3dp's deform_xyz and
// deform_cylinder): where a point goes, and the factors on its bead's
// cross-section and its head speed.
//
//   Cartesian    (x, y, z)        -> (FX, FY, FZ)
//   Cylindrical  (r, theta, z)    -> (FR, FTHETA, FZ) about (center_x, center_y):
//                x = cx + FR cos FTHETA, y = cy + FR sin FTHETA; theta is
//                atan2's, in (-pi, pi], radians
//
// Every formula may also use `layer` (gc-layers' number, first printed layer
// = 1) and `s` (mm of input path so far, travel included), and `pi`. The
// cross-section factor is FC times, by default, the local change of layer
// height dFZ/dz (Z = 0.3 z makes layers 0.3 times as thick; a central
// difference over 0.001 mm).
#include <array>
#include <optional>
#include <string>

#include "gcode/transform/expression.hpp"

namespace gcode {

enum class DeformFrame { Cartesian, Cylindrical };

struct DeformFormulas {
  DeformFrame frame = DeformFrame::Cartesian;
  std::array<std::string, 3> map{"x", "y", "z"};
  std::string width;   // FC; "" = 1
  std::string speed;   // FV; "" = 1
  double center_x = 0;
  double center_y = 0;
  bool layer_scale = true;  // the cross-section follows dFZ/dz
};

struct Point3 {
  double x = 0, y = 0, z = 0;
};

class DeformMap {
 public:
  // Throws ExpressionError whose message names the option, the formula and
  // the position: "--cylinder FR 'r + * z': Unexpected operator "*" found at character 5".
  explicit DeformMap(const DeformFormulas& formulas);

  const DeformFormulas& formulas() const { return formulas_; }
  // The layer and the path length the next evaluations see.
  void set_context(int layer, double path_length) {
    layer_ = layer;
    s_ = path_length;
  }
  Point3 apply(const Point3& p);
  // FC x dFZ/dz (or FC alone), at p.
  double section(const Point3& p);
  double speed(const Point3& p);  // FV at p
  // Whether the map is the identity by its text (x y z, no width or speed):
  // a caller may skip all work.
  bool identity() const;

 private:
  void bind(const Point3& p);
  double z_image(const Point3& p);

  DeformFormulas formulas_;
  double x_ = 0, y_ = 0, z_ = 0, r_ = 0, theta_ = 0, layer_ = 0, s_ = 0;
  std::array<std::optional<Expression>, 3> map_;
  std::optional<Expression> width_;
  std::optional<Expression> speed_;
};

}  // namespace gcode
