#include "gcode/procedural/shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace gcode::procedural {

namespace {

constexpr double kTurn = 2 * std::numbers::pi;
constexpr int kMinSteps = 8;
constexpr int kMaxSides = 1000;

bool rising(ShapeKind k) { return k != ShapeKind::Circle && k != ShapeKind::Spiral; }

bool from_mesh(ShapeKind k) { return k == ShapeKind::Vase; }

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

bool positive(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

bool parse_shape_kind(std::string_view name, ShapeKind& out) {
  for (ShapeKind k : {ShapeKind::Circle, ShapeKind::Spiral, ShapeKind::Helix, ShapeKind::Cylinder, ShapeKind::Polygon,
                      ShapeKind::Cone, ShapeKind::Vase})
    if (shape_kind_name(k) == name) {
      out = k;
      return true;
    }
  return false;
}

std::string_view shape_kind_name(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::Circle: return "circle";
    case ShapeKind::Spiral: return "spiral";
    case ShapeKind::Helix: return "helix";
    case ShapeKind::Cylinder: return "cylinder";
    case ShapeKind::Polygon: return "polygon";
    case ShapeKind::Cone: return "cone";
    case ShapeKind::Vase: break;
  }
  return "vase";
}

void ShapeOptions::validate() const {
  require(from_mesh(kind) || positive(diameter), "--diameter must be above 0");
  require(positive(layer_height), "--layer-height must be above 0");
  require(positive(line_width), "--line-width must be above 0");
  require(std::isfinite(center_x) && std::isfinite(center_y), "--center must be finite");
  require(positive(tolerance) && tolerance >= 2 * rounding,
          "--tolerance must be at least 0.002 mm (twice what 3 decimals of X and Y may round)");
  if (from_mesh(kind)) {
    require(positive(scale), "--scale must be above 0");
    require(bottom_layers >= 0 && bottom_layers <= 1000, "--bottom-layers must be 0..1000");
    require(positive(bed_width) && positive(bed_depth) && positive(bed_height), "--bed must be above 0");
    return;
  }
  if (rising(kind))
    require(positive(height) && height >= (kind == ShapeKind::Cylinder ? 2 : 1) * layer_height,
            kind == ShapeKind::Cylinder ? "--height must be at least two layer heights (the bottom and one turn)"
                                        : "--height must be at least one layer height");
  if (kind == ShapeKind::Cone) require(positive(top_diameter), "--top-diameter must be above 0");
  if (kind == ShapeKind::Polygon) require(sides >= 3 && sides <= kMaxSides, "--sides must be 3..1000");
  if (kind == ShapeKind::Cylinder) require(diameter > 2 * line_width, "--diameter must be above two line widths");
  if (kind == ShapeKind::Spiral) {
    require(std::isfinite(inner_diameter) && inner_diameter >= 0, "--inner-diameter must be 0 or above");
    const double inner = inner_diameter > 0 ? inner_diameter : 4 * line_width;
    require(inner < diameter, "--inner-diameter (default four line widths) must be below --diameter");
  }
}

ShapePath::ShapePath(const ShapeOptions& options, LaidPath laid) : options_(options), laid_(std::move(laid)) {
  options_.validate();
  bottom_layers_ = laid_.bottom_layers;
  turns_ = laid_.turns;
  pitch_ = laid_.pitch;
}

ShapePath::ShapePath(const ShapeOptions& options) : options_(options) {
  options_.validate();
  require(!from_mesh(options_.kind), "a vase is built from a mesh (--mesh MODEL.stl)");
  const ShapeOptions& o = options_;
  const double h = o.layer_height;
  spiral_inner_ = o.inner_diameter > 0 ? o.inner_diameter / 2 : 2 * o.line_width;
  if (!rising(o.kind)) {
    bottom_layers_ = 1;
    return;
  }
  if (o.kind == ShapeKind::Cylinder) {
    bottom_layers_ = 1;
    wall_base_ = h;
    const double bottom_angle = kTurn * (o.diameter / 2 - o.line_width / 2) / o.line_width;
    wall_angle_ = std::fmod(bottom_angle, kTurn);
  }
  const double wall = o.height - wall_base_;
  turns_ = std::max(1, static_cast<int>(std::ceil(wall / h - 1e-9)));
  pitch_ = wall / turns_;
}

double ShapePath::top() const {
  if (from_mesh(options_.kind)) return laid_.top;
  return rising(options_.kind) ? wall_base_ + pitch_ * turns_ : options_.layer_height;
}

double ShapePath::max_radius() const {
  const double d = options_.kind == ShapeKind::Cone ? std::max(options_.diameter, options_.top_diameter) : options_.diameter;
  return d / 2;
}

Box2 ShapePath::box() const {
  if (from_mesh(options_.kind)) return laid_.box;
  const double r = max_radius();
  return {options_.center_x - r, options_.center_y - r, options_.center_x + r, options_.center_y + r};
}

PathPoint ShapePath::start() const {
  if (from_mesh(options_.kind)) return laid_.start;
  const ShapeOptions& o = options_;
  const double r = o.kind == ShapeKind::Cylinder ? o.line_width / 2 : o.diameter / 2;
  // A flat layer (a cylinder's bottom too) lays its full bead from the start; a rising spiral ramps up from 0.
  const bool flat = !rising(o.kind) || o.kind == ShapeKind::Cylinder;
  return {o.center_x + r, o.center_y, flat ? o.layer_height : 0, flat ? o.layer_height : 0};
}

int ShapePath::steps_for(double radius) const {
  const double t = options_.tolerance - options_.rounding;
  const double angle = t < radius ? 2 * std::acos(1 - t / radius) : std::numbers::pi / 2;
  return std::max(kMinSteps, static_cast<int>(std::ceil(kTurn / angle)));
}

double ShapePath::wall_radius(double phi) const {
  const ShapeOptions& o = options_;
  if (o.kind != ShapeKind::Cone) return o.diameter / 2;
  return (o.diameter + (o.top_diameter - o.diameter) * phi / (kTurn * turns_)) / 2;
}

void ShapePath::layer(int i, ShapeLayer& out) const {
  if (from_mesh(options_.kind)) {
    out = laid_.layers[static_cast<std::size_t>(i)];
    return;
  }
  out.points.clear();
  out.bottom = false;
  out.start_bead = i == bottom_layers_ && options_.kind == ShapeKind::Cylinder ? 0 : -1;
  const ShapeOptions& o = options_;
  const double h = o.layer_height;
  const double r = o.diameter / 2;
  if (i < bottom_layers_) {
    if (o.kind == ShapeKind::Circle) {
      const int n = steps_for(r);
      for (int j = 1; j <= n; ++j) {
        const double a = kTurn * j / n;
        out.points.push_back({o.center_x + r * std::cos(a), o.center_y + r * std::sin(a), h, h});
      }
      return;
    }
    out.bottom = true;
    if (o.kind == ShapeKind::Spiral) flat_spiral(r, spiral_inner_, h, out);
    else flat_spiral(o.line_width / 2, r, h, out);
    return;
  }
  wall_turn(i - bottom_layers_, out);
}

// An Archimedean spiral one line width per turn, from r_from to r_to, at z.
void ShapePath::flat_spiral(double r_from, double r_to, double z, ShapeLayer& out) const {
  const ShapeOptions& o = options_;
  const double total = kTurn * std::fabs(r_to - r_from) / o.line_width;
  const double dr = (r_to - r_from) / total;  // per radian
  double phi = 0;
  while (phi < total) {
    const double widest = std::max(r_from + dr * phi, r_from + dr * (phi + std::numbers::pi / 2));
    phi = std::min(total, phi + kTurn / steps_for(widest));
    const double rr = r_from + dr * phi;
    out.points.push_back({o.center_x + rr * std::cos(phi), o.center_y + rr * std::sin(phi), z, o.layer_height});
  }
}

void ShapePath::wall_turn(int turn, ShapeLayer& out) const {
  const ShapeOptions& o = options_;
  const bool polygon = o.kind == ShapeKind::Polygon;
  const int n = polygon ? o.sides : steps_for(std::max(wall_radius(kTurn * turn), wall_radius(kTurn * (turn + 1))));
  for (int j = 1; j <= n; ++j) {
    const double phi = kTurn * (turn + static_cast<double>(j) / n);
    const double a = wall_angle_ + phi;
    const double r = wall_radius(phi);
    const double z = wall_base_ + pitch_ * phi / kTurn;
    out.points.push_back({o.center_x + r * std::cos(a), o.center_y + r * std::sin(a), z,
                          std::min(z - wall_base_, pitch_)});
  }
}

}  // namespace gcode::procedural
