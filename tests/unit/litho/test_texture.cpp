#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "gcode/litho/texture.hpp"

using gcode::litho::GreyImage;
using gcode::litho::Projection;
using gcode::litho::SpeedMapping;
using gcode::litho::TextureMapping;
using gcode::litho::TexturePiece;
using gcode::litho::TextureProjection;

namespace {

// 4 x 2 pixels, each a different grey: luma = 10 + 20 x + 100 y.
GreyImage tiles() {
  std::vector<std::uint8_t> px;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) px.push_back(static_cast<std::uint8_t>(10 + 20 * x + 100 * y));
  return {4, 2, std::move(px)};
}

TextureMapping mapping(Projection p, double width = 40) {
  TextureMapping m;
  m.projection = p;
  m.width = width;
  return m;
}

// Which tile a point lands on: -1 outside the picture.
int tile_at(const TextureProjection& proj, double x, double y, double z) {
  const auto uv = proj.uv(x, y, z);
  if (!uv) return -1;
  const auto p = gcode::litho::pixel_at(tiles(), *uv);
  return p.x + 4 * p.y;
}

}  // namespace

TEST_CASE("litho texture: projection names parse and print", "[litho][texture]") {
  for (const char* name : {"x", "y", "z", "cylinder", "sphere"}) {
    Projection p{};
    REQUIRE(gcode::litho::parse_projection(name, p));
    CHECK(gcode::litho::projection_name(p) == name);
  }
  Projection p{};
  CHECK_FALSE(gcode::litho::parse_projection("cube", p));
}

TEST_CASE("litho texture: planar projections map points to the picture seen from the front side and above", "[litho][texture]") {
  // 40 x 20 mm (aspect kept), centred on X = Y = 110, bottom edge on the bed.
  const TextureProjection y(mapping(Projection::Y), 4, 2);
  CHECK(y.height() == 20);
  CHECK(tile_at(y, 95, 0, 15) == 0);   // left, upper row
  CHECK(tile_at(y, 125, 0, 15) == 3);  // right, upper row
  CHECK(tile_at(y, 105, 50, 5) == 5);  // lower row; Y does not matter
  CHECK(tile_at(y, 131, 0, 5) == -1);
  CHECK(tile_at(y, 110, 0, 21) == -1);
  CHECK(tile_at(y, 110, 0, -1) == -1);
  const TextureProjection x(mapping(Projection::X), 4, 2);
  CHECK(tile_at(x, 0, 95, 15) == 0);  // seen from +X, right is +Y
  CHECK(tile_at(x, 0, 125, 5) == 7);
  const TextureProjection z(mapping(Projection::Z), 4, 2);
  CHECK(tile_at(z, 95, 115, 3) == 0);  // the picture's top at the back
  CHECK(tile_at(z, 125, 105, 3) == 7);
  TextureMapping shifted = mapping(Projection::Y);
  shifted.offset_u = 10;
  shifted.offset_v = 5;
  const TextureProjection s(shifted, 4, 2);
  CHECK(tile_at(s, 105, 0, 20) == 0);  // the picture moved 10 mm right and 5 mm up
  CHECK(tile_at(s, 95, 0, 20) == -1);
}

TEST_CASE("litho texture: the cylinder projection wraps once around with the centre facing the front", "[litho][texture]") {
  const TextureProjection c(mapping(Projection::Cylinder, 100), 4, 2);
  CHECK(c.height() == 50);
  const double r = 15;
  CHECK(tile_at(c, 110, 110 - r, 40) == 2);     // front: the middle of the picture
  CHECK(tile_at(c, 110 + r, 110, 40) == 3);     // right of the front, for a viewer outside
  CHECK(tile_at(c, 110 - r, 110, 40) == 1);
  CHECK(tile_at(c, 110 + 1, 110 + r, 40) == 3);  // going round counter-clockwise: the last column before the back seam
  CHECK(tile_at(c, 110 - 1, 110 + r, 40) == 0);  // and the first one after it
  CHECK(tile_at(c, 110, 110 - r, 10) == 6);     // lower row
  CHECK(tile_at(c, 110, 110 - r, 51) == -1);    // above the picture
  CHECK(tile_at(c, 110, 110, 10) == -1);        // on the axis
  // Same angle, any radius: the same pixel.
  CHECK(tile_at(c, 110 + 3, 110, 40) == tile_at(c, 110 + 40, 110, 40));
}

TEST_CASE("litho texture: the sphere projection maps latitude to rows and longitude to columns", "[litho][texture]") {
  TextureMapping m;
  m.projection = Projection::Sphere;
  m.center_z = 30;
  const TextureProjection s(m, 4, 2);
  CHECK(tile_at(s, 110, 110 - 1e-3, 30 + 20) == 2);  // near the north pole: top row
  CHECK(tile_at(s, 110, 110 - 20, 30 + 1) == 2);     // just above the equator, front
  CHECK(tile_at(s, 110, 110 - 20, 30 - 1) == 6);     // just below
  CHECK(tile_at(s, 110 + 20, 110, 25) == 7);
  CHECK(tile_at(s, 110, 110, 30) == -1);             // the centre itself
}

TEST_CASE("litho texture: texture sizes keep the aspect and bad mappings are refused", "[litho][texture]") {
  TextureMapping m = mapping(Projection::Y, 0);
  m.height = 10;
  CHECK(TextureProjection(m, 4, 2).width() == 20);
  m.height = 0;
  CHECK_THROWS_WITH(TextureProjection(m, 4, 2), Catch::Contains("needs the picture's --width or --height"));
  m.width = 30;
  m.keep_aspect = false;
  CHECK_THROWS_WITH(TextureProjection(m, 4, 2), Catch::Contains("both --width and --height"));
  m.height = 5;
  CHECK(TextureProjection(m, 4, 2).height() == 5);
  m.width = -1;
  CHECK_THROWS_WITH(TextureProjection(m, 4, 2), Catch::Contains("--width"));
}

TEST_CASE("litho texture: speed is low plus grey times the range or a binary pair", "[litho][texture]") {
  SpeedMapping s;
  s.low = 20;
  s.high = 60;
  CHECK(s.speed(0.0) == 20);
  CHECK(s.speed(1.0) == 60);
  CHECK(s.speed(std::uint8_t{51}) == Approx(20 + 0.2 * 40));
  s.invert = true;
  CHECK(s.speed(0.0) == 60);
  SpeedMapping b;
  b.binary = true;
  b.high = 40;
  b.threshold = 0.5;
  b.ratio = 0.65;
  CHECK(b.speed(0.2) == Approx(26));
  CHECK(b.speed(0.8) == 40);
  SpeedMapping bad;
  bad.low = 50;
  bad.high = 40;
  CHECK_THROWS_WITH(bad.validate(), Catch::Contains("--low (50 mm/s) must be above 0 and at most --high"));
  b.ratio = 1.5;
  CHECK_THROWS_WITH(b.validate(), Catch::Contains("--ratio"));
}

TEST_CASE("litho texture: a new speed keeps E per second when E scales by old speed over new", "[litho][texture]") {
  const double length = 2, e_old = 0.1, v_old = 40, v_new = 26;
  const double e_new = gcode::litho::constant_rate_extrusion(e_old, v_old, v_new);
  CHECK(e_new / (length / v_new) == Approx(e_old / (length / v_old)));
  CHECK(e_new > e_old);  // slower: a thicker bead
}

TEST_CASE("litho texture: a textured move changes speed only where the pixel changes", "[litho][texture]") {
  const TextureProjection y(mapping(Projection::Y), 4, 2);
  SpeedMapping s;
  s.low = 20;
  s.high = 60;
  std::vector<TexturePiece> pieces;
  // Along the upper row, from 10 mm left of the picture to its right edge.
  gcode::litho::texture_move(y, tiles(), s, {80, 0, 15}, {130, 0, 15}, 50, 0.2, pieces);
  REQUIRE(pieces.size() == 5);
  CHECK_FALSE(pieces[0].textured);
  CHECK(pieces[0].speed == 50);
  CHECK(pieces[0].end == Approx(0.2));
  for (int x = 0; x < 4; ++x) {
    const TexturePiece& p = pieces[static_cast<std::size_t>(x) + 1];
    CHECK(p.textured);
    CHECK(p.end == Approx(0.2 + 0.2 * (x + 1)));
    CHECK(p.speed == Approx(s.speed(static_cast<std::uint8_t>(10 + 20 * x))));
    CHECK(p.e_factor == Approx(50 / p.speed));
  }
  // E per second of every piece equals the original move's.
  const double e = 2.0, length = 50;
  double start = 0;
  for (const TexturePiece& p : pieces) {
    const double share = p.end - start;
    CHECK((share * e * p.e_factor) / (share * length / p.speed) == Approx(e / (length / 50)));
    start = p.end;
  }
}
