#pragma once
// Velocity painting: a picture projected onto a print, drawn by the head
// speed at a constant extruder rate (background.md §2; gc-litho --texture).
//
// Physics in two sentences: a bead's cross-section is A = q / v, so at a
// constant extruder rate q a slower head lays a thicker bead and a faster one
// a thinner bead, and the surface shows the picture. The extruder rate is
// kept, not the bead, because the extruder answers seconds late while the
// head answers at once; so when a piece's speed goes from v_old to v_new its
// E becomes E_old x v_old / v_new (E per second unchanged).
//
// Pure functions, no G-code: the stage that rewrites moves (mode 2) asks
// where a point falls on the picture, which speed that pixel means, and how
// to share a move into pieces that change speed only where the pixel does.
//
// Projections (u: picture left to right, v: top to bottom, both 0..1):
//   y         seen from the front (-Y): u along +X, v down along Z;
//   x         seen from the right (+X): u along +Y, v down along Z;
//   z         seen from above: u along +X, v down along -Y (picture top at the back);
//   cylinder  around the vertical axis through (center_x, center_y): u from
//             the angle, once around, the picture's centre facing the front
//             and running left to right for a viewer outside; v down along Z;
//   sphere    around (center_x, center_y, center_z): u from the longitude as
//             for the cylinder, v from the latitude (north pole = top row).
// Planar pictures are centred on center_x / center_y; the planar and
// cylinder pictures' bottom edge is at bottom_z. Offsets move the picture
// right (offset_u) and up (offset_v) in mm on its surface; for a cylinder
// `width` is the circumference one turn of the picture covers.
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "gcode/litho/image.hpp"

namespace gcode::litho {

enum class Projection : std::uint8_t { X, Y, Z, Cylinder, Sphere };

// "x", "y", "z", "cylinder", "sphere"; false for anything else.
bool parse_projection(std::string_view name, Projection& out);
std::string_view projection_name(Projection p);

struct TextureMapping {
  Projection projection = Projection::Cylinder;
  double center_x = 110;   // mm
  double center_y = 110;
  double center_z = 0;     // sphere only: height of the centre
  double bottom_z = 0;     // planar and cylinder: height of the picture's bottom edge
  double offset_u = 0;     // mm to the right on the picture's surface
  double offset_v = 0;     // mm up
  double width = 0;        // mm; 0 = from height and the picture's aspect
  double height = 0;       // mm; 0 = from width and the picture's aspect
  bool keep_aspect = true; // false: both sizes must be given
  // Throws std::invalid_argument naming the option that makes no sense.
  void validate() const;
};

struct UV {
  double u = 0;
  double v = 0;
};

class TextureProjection {
 public:
  // Resolves the picture's size in mm from the options and its aspect.
  TextureProjection(const TextureMapping& mapping, int image_width, int image_height);

  // Where the point lands on the picture; nothing when it lands outside
  // (beyond a planar picture's edges, above or below a cylinder's, or on a
  // projection's axis where the angle is undefined).
  std::optional<UV> uv(double x, double y, double z) const;
  double width() const { return width_; }    // mm (sphere: 0 if not given)
  double height() const { return height_; }
  const TextureMapping& mapping() const { return mapping_; }

 private:
  TextureMapping mapping_;
  double width_ = 0;
  double height_ = 0;
};

struct Pixel {
  int x = 0;
  int y = 0;
  std::uint8_t luma = 0;
};
// The pixel under (u, v), nearest (no blending: a speed changes only where the pixel does).
Pixel pixel_at(const GreyImage& image, UV uv);

struct SpeedMapping {
  double low = 26;          // mm/s for black (continuous mode)
  double high = 40;         // mm/s for white; the fast speed in binary mode
  bool binary = false;      // two speeds: dark pixels slow, light pixels fast
  double threshold = 0.5;   // binary: grey (0..1) below it is dark
  double ratio = 0.65;      // binary: slow = high x ratio (the globe used 1 : 0.6-0.7)
  bool invert = false;      // light = slow
  void validate() const;
  // Speed for a grey level 0 (black) .. 1 (white): low + grey x (high - low),
  // or the binary pair. Darker = slower = thicker bead, as in a lithophane.
  double speed(double grey) const;
  double speed(std::uint8_t luma) const { return speed(luma / 255.0); }
};

// E of a piece whose speed changes from v_old to v_new at a constant extruder rate.
inline double constant_rate_extrusion(double e_old, double v_old, double v_new) { return e_old * v_old / v_new; }

struct Vec3 {
  double x = 0;
  double y = 0;
  double z = 0;
};

// One piece of a textured move: it ends at `end` (a share of the move, 0..1].
struct TexturePiece {
  double end = 1;
  double speed = 0;      // mm/s; the original speed where the picture does not reach
  double e_factor = 1;   // E of the piece = its share of the move's E x e_factor (v_old / v_new)
  bool textured = false;
};

// Splits the straight move a -> b (original speed `speed` mm/s) into equal
// steps of at most `resolution` mm, looks up each step's pixel at its middle,
// and merges neighbouring steps on the same pixel value: the result changes
// speed only where the picture does. Appends to `out` (cleared first).
void texture_move(const TextureProjection& projection, const GreyImage& image, const SpeedMapping& speeds, Vec3 a,
                  Vec3 b, double speed, double resolution, std::vector<TexturePiece>& out);

}  // namespace gcode::litho
