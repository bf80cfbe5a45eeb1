#pragma once
// Printable primitives without a slicer (background.md §2): the path of a
// circle, a flat spiral, a helix (a thin cylinder wall printed as one rising
// spiral: no seam, no layer change), a cylinder (a filled bottom as a flat
// spiral, then the helix wall), a polygon and a cone, as points with the
// bead height under each.
//
// Geometry, all about (center_x, center_y); diameters are the path's (the
// bead's centre line):
//   circle    one turn at z = layer height;
//   spiral    flat, from the diameter inward to inner_diameter, one line
//             width between neighbouring turns, at z = layer height;
//   helix     z rises by the pitch per turn from the bed to the height; the
//             pitch is the layer height, shortened so that a whole number of
//             turns reaches the height exactly;
//   cone      a helix whose diameter goes linearly from `diameter` at the
//             bottom to `top_diameter` at the top;
//   polygon   a helix through the corners of a regular polygon (`sides`,
//             corners on the diameter, the first on +X), straight edges;
//   cylinder  a flat spiral from the centre outward to the diameter (the
//             bottom, one layer), then the helix wall from where it ends;
//   vase      a mesh's outer wall as one rising spiral on a filled bottom
//             (mesh_vase.hpp builds its layers: a LaidPath).
// The first turn of every rising spiral ramps up from what it stands on
// (the bed, the cylinder's bottom): its bead grows from nothing to the full
// layer height, so the spiral starts on the bed and every later point lies
// one pitch above the point under it. bead height = min(z - base, pitch).
//
// Points along curves come at a chord tolerance: a chord of angle a on
// radius r deviates r (1 - cos(a/2)) from its arc, so each turn gets the
// fewest equal steps that keep that within the tolerance (at the turn's
// largest radius), less the rounding of written coordinates.
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/geometry.hpp"

namespace gcode::procedural {

enum class ShapeKind { Circle, Spiral, Helix, Cylinder, Polygon, Cone, Vase };

// "circle", "spiral", "helix", "cylinder", "polygon", "cone", "vase"; false for anything else.
bool parse_shape_kind(std::string_view name, ShapeKind& out);
std::string_view shape_kind_name(ShapeKind kind);

struct ShapeOptions {
  ShapeKind kind = ShapeKind::Helix;
  double diameter = 60;        // mm, the path's; a cone's at the bottom
  double top_diameter = 30;    // mm, a cone's at the top
  double inner_diameter = 0;   // mm, where a flat spiral ends (0 = two line widths)
  double height = 20;          // mm, rising shapes
  double layer_height = 0.3;   // mm, the pitch of a rising spiral
  double line_width = 0.5;     // mm
  int sides = 6;               // polygon
  double center_x = 110;       // mm
  double center_y = 110;
  double tolerance = 0.01;     // mm, chord error along curves
  double rounding = 0.0008;    // mm, what writing the coordinates may add (3 decimals: 0.0005 x sqrt 2)
  // A vase from a mesh:
  double scale = 1;            // of the model's coordinates
  int bottom_layers = 3;       // filled layers under the wall
  double bed_width = 220, bed_depth = 220, bed_height = 250;  // mm, what the model must fit in
  // Throws std::invalid_argument naming the option that makes no sense.
  void validate() const;
};

struct PathPoint {
  double x = 0, y = 0, z = 0;
  double bead = 0;  // bead height laid on the way to this point (at this point)
  bool travel = false;  // reached by a travel, not a bead (between a flat fill's pieces and layers)
};

// One layer of the path: a rising spiral's turn, or a flat part.
struct ShapeLayer {
  std::vector<PathPoint> points;  // from the end of the previous layer (the first layer: from start())
  bool bottom = false;            // a cylinder's filled bottom (;TYPE:SKIN), else the wall
  // The bead height where the layer begins, when it is not the previous
  // point's: a cylinder's wall starts from nothing on the bottom's edge.
  double start_bead = -1;
};

// A path built elsewhere (a vase from a mesh): its layers and what the
// header says about it.
struct LaidPath {
  std::vector<ShapeLayer> layers;
  PathPoint start;
  int bottom_layers = 0;
  int turns = 0;
  double pitch = 0;
  double top = 0;
  Box2 box;
  std::vector<std::string> parameters;  // "name = value" lines for the header
};

class ShapePath {
 public:
  explicit ShapePath(const ShapeOptions& options);  // validates
  ShapePath(const ShapeOptions& options, LaidPath laid);

  const ShapeOptions& options() const { return options_; }
  int layer_count() const { return bottom_layers_ + turns_; }
  int turns() const { return turns_; }             // turns of the rising wall (flat shapes: 0)
  double pitch() const { return pitch_; }          // mm of rise per turn (flat shapes: 0)
  double top() const;                              // highest Z of the path
  PathPoint start() const;                         // where the path begins (a rising spiral: bead 0)
  // The points of layer i (0-based); `out` is cleared first.
  void layer(int i, ShapeLayer& out) const;
  // The XY extent of the path (radius about the centre).
  double max_radius() const;
  Box2 box() const;                                // the print's XY box
  const LaidPath& laid() const { return laid_; }   // a built path's (empty for a primitive)

 private:
  void flat_spiral(double r_from, double r_to, double z, ShapeLayer& out) const;
  void wall_turn(int turn, ShapeLayer& out) const;
  int steps_for(double radius) const;
  double wall_radius(double phi) const;  // phi from the wall's start angle

  ShapeOptions options_;
  int bottom_layers_ = 0;
  int turns_ = 0;
  double pitch_ = 0;
  double wall_base_ = 0;      // Z the wall stands on
  double wall_angle_ = 0;     // angle where the wall starts
  double spiral_inner_ = 0;   // flat spiral: inner radius
  LaidPath laid_;
};

}  // namespace gcode::procedural
