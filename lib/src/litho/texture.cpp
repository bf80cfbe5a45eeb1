#include "gcode/litho/texture.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace gcode::litho {

namespace {

bool finite(double v) { return std::isfinite(v); }

double wrap01(double u) { return u - std::floor(u); }

}  // namespace

bool parse_projection(std::string_view name, Projection& out) {
  static constexpr std::pair<std::string_view, Projection> kNames[] = {{"x", Projection::X},
                                                                       {"y", Projection::Y},
                                                                       {"z", Projection::Z},
                                                                       {"cylinder", Projection::Cylinder},
                                                                       {"sphere", Projection::Sphere}};
  for (const auto& [text, p] : kNames)
    if (name == text) {
      out = p;
      return true;
    }
  return false;
}

std::string_view projection_name(Projection p) {
  switch (p) {
    case Projection::X:
      return "x";
    case Projection::Y:
      return "y";
    case Projection::Z:
      return "z";
    case Projection::Cylinder:
      return "cylinder";
    case Projection::Sphere:
      break;
  }
  return "sphere";
}

void TextureMapping::validate() const {
  for (double v : {center_x, center_y, center_z, bottom_z, offset_u, offset_v})
    if (!finite(v)) throw std::invalid_argument("texture positions and offsets must be numbers");
  if (!(finite(width) && width >= 0)) throw std::invalid_argument("--width must be 0 (from the aspect) or above");
  if (!(finite(height) && height >= 0)) throw std::invalid_argument("--height must be 0 (from the aspect) or above");
  if (projection == Projection::Sphere) return;
  if (width == 0 && height == 0)
    throw std::invalid_argument(fmt::format("the {} projection needs the picture's --width or --height in mm",
                                            projection_name(projection)));
  if (!keep_aspect && (width == 0 || height == 0))
    throw std::invalid_argument("without keeping the aspect both --width and --height are needed");
}

TextureProjection::TextureProjection(const TextureMapping& mapping, int image_width, int image_height)
    : mapping_(mapping), width_(mapping.width), height_(mapping.height) {
  mapping_.validate();
  if (image_width <= 0 || image_height <= 0) throw std::invalid_argument("TextureProjection: empty picture");
  const double aspect = static_cast<double>(image_height) / image_width;
  if (width_ > 0 && height_ == 0) height_ = width_ * aspect;
  if (height_ > 0 && width_ == 0) width_ = height_ / aspect;
}

std::optional<UV> TextureProjection::uv(double x, double y, double z) const {
  const TextureMapping& m = mapping_;
  UV r;
  switch (m.projection) {
    case Projection::Y:
    case Projection::X:
      r.u = ((m.projection == Projection::Y ? x - m.center_x : y - m.center_y) - m.offset_u) / width_ + 0.5;
      r.v = 1 - (z - m.bottom_z - m.offset_v) / height_;
      break;
    case Projection::Z:
      r.u = (x - m.center_x - m.offset_u) / width_ + 0.5;
      r.v = 0.5 - (y - m.center_y - m.offset_v) / height_;
      break;
    case Projection::Cylinder:
    case Projection::Sphere: {
      const double dx = x - m.center_x, dy = y - m.center_y;
      const double radial = std::hypot(dx, dy);
      const double dz = z - m.center_z;
      const bool sphere = m.projection == Projection::Sphere;
      if (radial < 1e-9 && (!sphere || std::abs(dz) < 1e-9)) return std::nullopt;
      // Angle from the front (-Y), counter-clockwise seen from above: for a
      // viewer outside that runs left to right.
      const double angle = std::atan2(dy, dx) + std::numbers::pi / 2;
      r.u = wrap01(0.5 + angle / (2 * std::numbers::pi) - (width_ > 0 ? m.offset_u / width_ : 0));
      if (sphere) {
        r.v = 0.5 - std::atan2(dz, radial) / std::numbers::pi + (height_ > 0 ? m.offset_v / height_ : 0);
      } else {
        r.v = 1 - (z - m.bottom_z - m.offset_v) / height_;
      }
      break;
    }
  }
  if (r.u < 0 || r.u > 1 || r.v < 0 || r.v > 1) return std::nullopt;
  return r;
}

Pixel pixel_at(const GreyImage& image, UV uv) {
  Pixel p;
  p.x = std::clamp(static_cast<int>(std::floor(uv.u * image.width())), 0, image.width() - 1);
  p.y = std::clamp(static_cast<int>(std::floor(uv.v * image.height())), 0, image.height() - 1);
  p.luma = image.at(p.x, p.y);
  return p;
}

void SpeedMapping::validate() const {
  if (!(finite(high) && high > 0)) throw std::invalid_argument("--high must be above 0 mm/s");
  if (binary) {
    if (!(finite(threshold) && threshold >= 0 && threshold <= 1))
      throw std::invalid_argument("--binary takes a threshold from 0 to 1");
    if (!(finite(ratio) && ratio > 0 && ratio <= 1)) throw std::invalid_argument("--ratio must be above 0 and at most 1");
  } else if (!(finite(low) && low > 0 && low <= high)) {
    throw std::invalid_argument(fmt::format("--low ({} mm/s) must be above 0 and at most --high ({} mm/s)", low, high));
  }
}

double SpeedMapping::speed(double grey) const {
  grey = std::clamp(grey, 0.0, 1.0);
  if (invert) grey = 1 - grey;
  if (binary) return grey < threshold ? high * ratio : high;
  return low + grey * (high - low);
}

void texture_move(const TextureProjection& projection, const GreyImage& image, const SpeedMapping& speeds, Vec3 a,
                  Vec3 b, double speed, double resolution, std::vector<TexturePiece>& out) {
  out.clear();
  const double dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
  const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
  const int steps = std::max(1, static_cast<int>(std::ceil(length / resolution - 1e-9)));
  for (int i = 0; i < steps; ++i) {
    const double mid = (i + 0.5) / steps;
    TexturePiece piece;
    piece.end = static_cast<double>(i + 1) / steps;
    piece.speed = speed;
    if (const auto uv = projection.uv(a.x + dx * mid, a.y + dy * mid, a.z + dz * mid)) {
      piece.speed = speeds.speed(pixel_at(image, *uv).luma);
      piece.textured = true;
    }
    piece.e_factor = speed / piece.speed;
    if (!out.empty() && out.back().speed == piece.speed && out.back().textured == piece.textured) {
      out.back().end = piece.end;
    } else {
      out.push_back(piece);
    }
  }
  out.back().end = 1;
}

}  // namespace gcode::litho
