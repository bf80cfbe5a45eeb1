#pragma once
// A picture laid onto a base shape as a thickness, in millimetres.
//
// Physics in two sentences: the light that passes a lithophane falls off with
// its thickness, so each point's thickness is min + tone(pixel) x (max - min)
// (image.hpp's ToneCurve: darker = thicker). The map is a continuous function
// of position (bilinear between pixel centres), so the paths and the STL can
// sample it at any resolution and agree with each other.
//
// Coordinates: `s` runs along the base surface (mm) and `z` upwards from the
// bed (mm); the thickness stands out from the base at right angles.
//   flat:     a plate standing upright, the picture's width along X (s = x),
//             its height along Z, thickness along Y; seen from the front of
//             the printer (-Y, the flat side) the picture reads the right way.
//   cylinder: the picture wrapped once around a base circle of `diameter`,
//             thickness outward; s is the arc length on the base circle,
//             counter-clockwise seen from above (so the picture reads the right
//             way from outside), starting at +X.
// The picture keeps its aspect unless both width and height are given. A
// `border` is a frame at full thickness around the picture (flat: all four
// sides; cylinder: top and bottom), added outside the picture's area.
#include <cmath>
#include <cstdint>
#include <vector>

#include "gcode/litho/image.hpp"

namespace gcode::litho {

enum class LithoShape : std::uint8_t { Flat, Cylinder };

// A position on the bed, mm.
struct Point {
  double x = 0;
  double y = 0;
};

inline double distance(Point a, Point b) { return std::hypot(b.x - a.x, b.y - a.y); }

struct HeightMapOptions {
  LithoShape shape = LithoShape::Flat;
  double width = 100;        // flat: plate width in mm (0 = from height and aspect)
  double height = 0;         // mm, border included; 0 = from the picture's aspect
  double diameter = 54.8;    // cylinder: diameter of the base (inner) surface, mm (the paper's cylinders)
  double min_thickness = 0.8;  // mm, where the picture is lightest
  double max_thickness = 3.0;  // mm, where it is darkest
  double border = 0;         // mm of frame at max thickness
  ToneOptions tone;
  // Throws std::invalid_argument naming the option that makes no sense.
  void validate() const;
};

class HeightMap {
 public:
  // Throws std::invalid_argument for bad options or an empty image.
  HeightMap(GreyImage image, const HeightMapOptions& options);

  LithoShape shape() const { return options_.shape; }
  bool closed() const { return options_.shape == LithoShape::Cylinder; }
  // Length of the base along s: the plate width, or the base circumference.
  double length() const { return length_; }
  // Height of the lithophane, border included.
  double height() const { return height_; }
  // Cylinder: radius of the base (inner) surface; 0 for a flat plate.
  double base_radius() const { return closed() ? options_.diameter / 2 : 0; }
  double min_thickness() const { return options_.min_thickness; }
  double max_thickness() const { return options_.max_thickness; }
  const HeightMapOptions& options() const { return options_; }
  const GreyImage& image() const { return image_; }

  // Thickness in mm at (s, z); s and z are clamped into the plate (wrapped
  // around for a cylinder).
  double thickness(double s, double z) const;
  // The share of the thickness range at (s, z), 0..1 (1 in the border).
  double fraction(double s, double z) const;
  // The thickness at a fixed z is linear in s between knots: the pixel
  // centres (and the border's edges, where it jumps). Appends the knots
  // strictly between s0 and s1 (s0 < s1; a cylinder's s may run past one
  // turn) to `out` in increasing order.
  void knots(double s0, double s1, std::vector<double>& out) const;
  // Bed XY of the point `depth` mm out from the base at `s`, for a
  // lithophane standing on (center_x, center_y): a flat plate's base face
  // lies max_thickness / 2 in front of the centre line (so the plate's
  // bounding box is centred), a cylinder's axis is on the centre.
  Point place(double s, double depth, double center_x, double center_y) const;
  // The inverse of place: s (a cylinder's in [0, length)) and depth of a bed point.
  void locate(Point p, double center_x, double center_y, double& s, double& depth) const;
  // Where (s, z) falls on the picture: u 0..1 left to right, v 0..1 top to
  // bottom; false in the border.
  bool image_uv(double s, double z, double& u, double& v) const;

 private:
  GreyImage image_;
  HeightMapOptions options_;
  ToneCurve tone_;
  double length_ = 0;
  double height_ = 0;
};

}  // namespace gcode::litho
