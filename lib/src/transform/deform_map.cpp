#include "gcode/transform/deform_map.hpp"

#include <cmath>

#include <fmt/format.h>

namespace gcode {

namespace {

constexpr double kStep = 0.001;  // mm, the central difference of dFZ/dz

}  // namespace

DeformMap::DeformMap(const DeformFormulas& f) : formulas_(f) {
  const bool cyl = f.frame == DeformFrame::Cylindrical;
  ExpressionVariables vars = cyl ? ExpressionVariables{{"r", &r_}, {"theta", &theta_}, {"z", &z_}}
                                 : ExpressionVariables{{"x", &x_}, {"y", &y_}, {"z", &z_}};
  vars.push_back({"layer", &layer_});
  vars.push_back({"s", &s_});
  const char* option = cyl ? "--cylinder" : "--xyz";
  const char* names[3] = {cyl ? "FR" : "FX", cyl ? "FTHETA" : "FY", "FZ"};
  auto make = [&](const std::string& text, const std::string& label) {
    try {
      return Expression(text, vars);
    } catch (const ExpressionError& e) {
      throw ExpressionError(fmt::format("{} '{}': {}", label, text, e.what()), e.position);
    }
  };
  for (std::size_t i = 0; i < 3; ++i) map_[i].emplace(make(f.map[i], fmt::format("{} {}", option, names[i])));
  if (!f.width.empty()) width_.emplace(make(f.width, "--width FC"));
  if (!f.speed.empty()) speed_.emplace(make(f.speed, "--speed FV"));
}

bool DeformMap::identity() const {
  return formulas_.frame == DeformFrame::Cartesian && formulas_.map[0] == "x" && formulas_.map[1] == "y" &&
         formulas_.map[2] == "z" && formulas_.width.empty() && formulas_.speed.empty();
}

void DeformMap::bind(const Point3& p) {
  x_ = p.x, y_ = p.y, z_ = p.z;
  if (formulas_.frame == DeformFrame::Cylindrical) {
    const double dx = p.x - formulas_.center_x, dy = p.y - formulas_.center_y;
    r_ = std::hypot(dx, dy);
    theta_ = std::atan2(dy, dx);
  }
}

Point3 DeformMap::apply(const Point3& p) {
  bind(p);
  const double a = map_[0]->evaluate(), b = map_[1]->evaluate(), z = map_[2]->evaluate();
  if (formulas_.frame == DeformFrame::Cartesian) return {a, b, z};
  return {formulas_.center_x + a * std::cos(b), formulas_.center_y + a * std::sin(b), z};
}

double DeformMap::z_image(const Point3& p) {
  bind(p);
  return map_[2]->evaluate();
}

double DeformMap::section(const Point3& p) {
  double factor = 1;
  if (formulas_.layer_scale)
    factor = (z_image({p.x, p.y, p.z + kStep}) - z_image({p.x, p.y, p.z - kStep})) / (2 * kStep);
  if (width_) {
    bind(p);
    factor *= width_->evaluate();
  }
  return factor;
}

double DeformMap::speed(const Point3& p) {
  if (!speed_) return 1;
  bind(p);
  return speed_->evaluate();
}

}  // namespace gcode
