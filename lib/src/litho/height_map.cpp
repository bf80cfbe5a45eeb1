#include "gcode/litho/height_map.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace gcode::litho {

namespace {

bool finite_non_negative(double v) { return std::isfinite(v) && v >= 0; }

}  // namespace

void HeightMapOptions::validate() const {
  if (!(std::isfinite(min_thickness) && min_thickness > 0)) throw std::invalid_argument("--min must be above 0 mm");
  if (!std::isfinite(max_thickness) || !(min_thickness < max_thickness))
    throw std::invalid_argument(
        fmt::format("--min ({} mm) must be less than --max ({} mm)", min_thickness, max_thickness));
  if (!finite_non_negative(width)) throw std::invalid_argument("--width must be 0 (from the aspect) or above");
  if (!finite_non_negative(height)) throw std::invalid_argument("--height must be 0 (from the aspect) or above");
  if (!finite_non_negative(border)) throw std::invalid_argument("--border must be 0 or above");
  if (shape == LithoShape::Flat && width == 0 && height == 0)
    throw std::invalid_argument("a flat lithophane needs --width or --height");
  if (shape == LithoShape::Cylinder && !(std::isfinite(diameter) && diameter > 0))
    throw std::invalid_argument("--diameter must be above 0 mm");
  tone.validate();
}

HeightMap::HeightMap(GreyImage image, const HeightMapOptions& options)
    : image_(std::move(image)), options_(options), tone_(options.tone) {
  options_.validate();
  if (image_.empty()) throw std::invalid_argument("HeightMap: empty image");
  const double aspect = static_cast<double>(image_.height()) / image_.width();  // picture height / width
  const double b = options_.border;
  if (options_.shape == LithoShape::Cylinder) {
    length_ = std::numbers::pi * options_.diameter;
    height_ = options_.height > 0 ? options_.height : length_ * aspect + 2 * b;
  } else if (options_.width > 0) {
    length_ = options_.width;
    height_ = options_.height > 0 ? options_.height : (length_ - 2 * b) * aspect + 2 * b;
  } else {
    height_ = options_.height;
    length_ = (height_ - 2 * b) / aspect + 2 * b;
  }
  const bool side_border = options_.shape == LithoShape::Flat;
  if (!(height_ > 2 * b) || (side_border && !(length_ > 2 * b)))
    throw std::invalid_argument(
        fmt::format("--border {} mm leaves no room for the picture on a {:.1f} x {:.1f} mm lithophane", b, length_,
                    height_));
}

Point HeightMap::place(double s, double depth, double center_x, double center_y) const {
  if (closed()) {
    const double radius = base_radius();
    const double angle = s / radius;
    return {center_x + (radius + depth) * std::cos(angle), center_y + (radius + depth) * std::sin(angle)};
  }
  return {center_x - length_ / 2 + s, center_y - options_.max_thickness / 2 + depth};
}

void HeightMap::locate(Point p, double center_x, double center_y, double& s, double& depth) const {
  if (closed()) {
    const double radius = base_radius();
    double angle = std::atan2(p.y - center_y, p.x - center_x);
    if (angle < 0) angle += 2 * std::numbers::pi;
    s = std::min(angle * radius, std::nextafter(length_, 0.0));
    depth = std::hypot(p.x - center_x, p.y - center_y) - radius;
    return;
  }
  s = p.x - (center_x - length_ / 2);
  depth = p.y - (center_y - options_.max_thickness / 2);
}

bool HeightMap::image_uv(double s, double z, double& u, double& v) const {
  const double b = options_.border;
  z = std::clamp(z, 0.0, height_);
  if (z < b || z > height_ - b) return false;
  v = (height_ - b - z) / (height_ - 2 * b);
  if (closed()) {
    u = s / length_;
    u -= std::floor(u);
    return true;
  }
  s = std::clamp(s, 0.0, length_);
  if (s < b || s > length_ - b) return false;
  u = (s - b) / (length_ - 2 * b);
  return true;
}

double HeightMap::fraction(double s, double z) const {
  double u = 0, v = 0;
  if (!image_uv(s, z, u, v)) return 1.0;
  const int w = image_.width();
  const int h = image_.height();
  // Bilinear between pixel centres; the tone is applied to the pixels, then
  // blended, so a sharp edge stays a straight ramp between two thicknesses.
  double px = u * w - 0.5;
  double py = std::clamp(v * h - 0.5, 0.0, static_cast<double>(h - 1));
  int x0 = 0, x1 = 0;
  double fx = 0;
  if (closed()) {
    const double fl = std::floor(px);
    fx = px - fl;
    x0 = static_cast<int>(fl) % w;
    if (x0 < 0) x0 += w;
    x1 = (x0 + 1) % w;
  } else {
    px = std::clamp(px, 0.0, static_cast<double>(w - 1));
    x0 = static_cast<int>(px);
    x1 = std::min(x0 + 1, w - 1);
    fx = px - x0;
  }
  const int y0 = static_cast<int>(py);
  const int y1 = std::min(y0 + 1, h - 1);
  const double fy = py - y0;
  const double top = tone_(image_.at(x0, y0)) * (1 - fx) + tone_(image_.at(x1, y0)) * fx;
  const double bottom = tone_(image_.at(x0, y1)) * (1 - fx) + tone_(image_.at(x1, y1)) * fx;
  return top * (1 - fy) + bottom * fy;
}

void HeightMap::knots(double s0, double s1, std::vector<double>& out) const {
  const double b = closed() ? 0.0 : options_.border;
  const double picture = length_ - 2 * b;  // s span of the picture
  const double pixel = picture / image_.width();
  auto add = [&](double k) {
    if (k > s0 && k < s1) out.push_back(k);
  };
  if (!closed() && b > 0) add(b);
  // Pixel centre i sits at b + (i + 0.5) x pixel (a cylinder's repeat every turn).
  const double first = std::ceil((s0 - b) / pixel - 0.5);
  for (double i = std::max(first, closed() ? first : 0.0); ; ++i) {
    if (!closed() && i >= image_.width()) break;
    const double k = b + (i + 0.5) * pixel;
    if (k >= s1) break;
    add(k);
  }
  if (!closed() && b > 0) add(length_ - b);
}

double HeightMap::thickness(double s, double z) const {
  return options_.min_thickness + fraction(s, z) * (options_.max_thickness - options_.min_thickness);
}

}  // namespace gcode::litho
