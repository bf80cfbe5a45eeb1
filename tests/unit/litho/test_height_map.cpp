#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "gcode/litho/height_map.hpp"
#include "litho_support.hpp"

using gcode::litho::HeightMap;
using gcode::litho::HeightMapOptions;
using gcode::litho::LithoShape;

namespace {

// Luma of the horizontal gradient fixture between pixel centres, by hand:
// pixel x holds round(255 x / (w - 1)) and sits at s = (x + 0.5) W / w.
double gradient_luma(double s, double plate_width, int w) {
  double px = s / plate_width * w - 0.5;
  px = std::clamp(px, 0.0, static_cast<double>(w - 1));
  const int x0 = static_cast<int>(px);
  const int x1 = std::min(x0 + 1, w - 1);
  const double f = px - x0;
  auto luma = [&](int x) { return std::round(255.0 * x / (w - 1)); };
  return luma(x0) * (1 - f) + luma(x1) * f;
}

}  // namespace

TEST_CASE("litho height map: a flat plate is 100 mm wide by default with the picture's aspect", "[litho][height_map]") {
  const HeightMap map(littest::gradient(64, 32), HeightMapOptions{});
  CHECK(map.length() == 100);
  CHECK(map.height() == 50);
  CHECK_FALSE(map.closed());
  HeightMapOptions o;
  o.width = 0;
  o.height = 40;
  const HeightMap by_height(littest::gradient(64, 32), o);
  CHECK(by_height.length() == Approx(80));
}

TEST_CASE("litho height map: thickness at sampled points equals the image mapping", "[litho][height_map]") {
  const HeightMap map(littest::gradient(64, 32), HeightMapOptions{});
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> s_dist(0, 100), z_dist(0, 50);
  for (int i = 0; i < 500; ++i) {
    const double s = s_dist(rng), z = z_dist(rng);
    const double expected = 0.8 + (1 - gradient_luma(s, 100, 64) / 255) * 2.2;
    INFO("s " << s << " z " << z);
    REQUIRE(map.thickness(s, z) == Approx(expected).margin(1e-12));
  }
  // Dark left edge is the thickest, the light right edge the thinnest.
  CHECK(map.thickness(0, 10) == Approx(3.0));
  CHECK(map.thickness(100, 10) == Approx(0.8));
}

TEST_CASE("litho height map: the top of the picture is the top of the plate", "[litho][height_map]") {
  // Vertical gradient: black top row, white bottom row.
  const HeightMap map(littest::gradient(10, 20, true), HeightMapOptions{});
  REQUIRE(map.height() == Approx(200));
  CHECK(map.thickness(50, map.height()) == Approx(3.0));
  CHECK(map.thickness(50, 0) == Approx(0.8));
  // Row centres: row y sits at z = H - (y + 0.5) H / 20.
  for (int y = 0; y < 20; ++y) {
    const double z = map.height() - (y + 0.5) * map.height() / 20;
    CHECK(map.thickness(50, z) == Approx(0.8 + (1 - std::round(255.0 * y / 19) / 255) * 2.2));
  }
}

TEST_CASE("litho height map: invert makes light thick and a border frames the picture at full thickness", "[litho][height_map]") {
  HeightMapOptions o;
  o.tone.invert = true;
  o.border = 5;
  const HeightMap map(littest::gradient(64, 32), o);
  CHECK(map.height() == Approx((100 - 10) * 0.5 + 10));
  for (double s : {0.0, 2.0, 4.99, 95.01, 100.0}) CHECK(map.thickness(s, 20) == Approx(3.0));
  for (double z : {0.0, 4.9, map.height() - 4.9}) CHECK(map.thickness(50, z) == Approx(3.0));
  // Inside, the picture spans 5..95 mm; inverted, its light right edge is thick.
  CHECK(map.thickness(95, 20) == Approx(3.0));
  CHECK(map.thickness(5, 20) == Approx(0.8));
  double u = 0, v = 0;
  CHECK(map.image_uv(50, map.height() / 2, u, v));
  CHECK(u == Approx(0.5));
  CHECK(v == Approx(0.5));
  CHECK_FALSE(map.image_uv(3, 20, u, v));
}

TEST_CASE("litho height map: a cylinder wraps the picture once around its base and joins the two edges", "[litho][height_map]") {
  HeightMapOptions o;
  o.shape = LithoShape::Cylinder;
  const HeightMap map(littest::gradient(64, 32), o);
  CHECK(map.closed());
  CHECK(map.length() == Approx(std::numbers::pi * 54.8));
  CHECK(map.height() == Approx(map.length() / 2));
  CHECK(map.base_radius() == Approx(27.4));
  // At the seam the first (black) and last (white) columns meet half way.
  CHECK(map.thickness(0, 20) == Approx(0.8 + 0.5 * 2.2));
  CHECK(map.thickness(map.length(), 20) == Approx(map.thickness(0, 20)));
  CHECK(map.thickness(-1, 20) == Approx(map.thickness(map.length() - 1, 20)));
  // Pixel centres away from the seam map exactly.
  const double pitch = map.length() / 64;
  CHECK(map.thickness(10.5 * pitch, 20) == Approx(0.8 + (1 - std::round(255.0 * 10 / 63) / 255) * 2.2));
}

TEST_CASE("litho height map: impossible height map options fail with the option named", "[litho][height_map]") {
  HeightMapOptions o;
  o.min_thickness = 3;
  o.max_thickness = 3;
  CHECK_THROWS_WITH(HeightMap(littest::gradient(4, 4), o), Catch::Contains("--min (3 mm) must be less than --max"));
  o = {};
  o.min_thickness = 0;
  CHECK_THROWS_WITH(HeightMap(littest::gradient(4, 4), o), Catch::Contains("--min must be above 0"));
  o = {};
  o.border = 60;
  CHECK_THROWS_WITH(HeightMap(littest::gradient(4, 4), o), Catch::Contains("--border 60 mm leaves no room"));
  o = {};
  o.shape = LithoShape::Cylinder;
  o.diameter = -1;
  CHECK_THROWS_WITH(HeightMap(littest::gradient(4, 4), o), Catch::Contains("--diameter"));
  o = {};
  o.width = 0;
  CHECK_THROWS_WITH(HeightMap(littest::gradient(4, 4), o), Catch::Contains("--width or --height"));
  CHECK_THROWS_AS(HeightMap(gcode::litho::GreyImage{}, HeightMapOptions{}), std::invalid_argument);
}

TEST_CASE("litho height map: knots are the pixel centres and the thickness is linear between them", "[litho][height_map]") {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> luma(0, 255);
  std::vector<std::uint8_t> px(12 * 4);
  for (auto& p : px) p = static_cast<std::uint8_t>(luma(rng));
  for (LithoShape shape : {LithoShape::Flat, LithoShape::Cylinder}) {
    HeightMapOptions o;
    o.shape = shape;
    o.width = 30;
    o.diameter = 10;
    o.border = shape == LithoShape::Flat ? 2 : 0;
    const HeightMap map(gcode::litho::GreyImage(12, 4, px), o);
    const double z = map.height() / 2;
    std::vector<double> k;
    map.knots(0, map.length(), k);
    // Flat: the border's two edges and the 12 pixel centres; a cylinder's 12 centres.
    REQUIRE(k.size() == (shape == LithoShape::Flat ? 14u : 12u));
    const double b = o.border;
    const double pixel = (map.length() - 2 * b) / 12;
    for (int i = 0; i < 12; ++i) CHECK(k[static_cast<std::size_t>(i) + (b > 0)] == Approx(b + (i + 0.5) * pixel));
    CHECK(std::is_sorted(k.begin(), k.end()));
    // Between two knots, the thickness at any point is on their chord.
    for (std::size_t i = 0; i + 1 < k.size(); ++i) {
      const double a = k[i] + 1e-9, c = k[i + 1] - 1e-9;
      for (double f : {0.25, 0.5, 0.8}) {
        const double s = a + (c - a) * f;
        CHECK(map.thickness(s, z) ==
              Approx(map.thickness(a, z) + (map.thickness(c, z) - map.thickness(a, z)) * f).margin(1e-6));
      }
    }
    // Only the knots strictly inside the range; a cylinder's repeat past one turn.
    std::vector<double> part;
    map.knots(k[2], k[5], part);
    CHECK(part.size() == 2);
    if (map.closed()) {
      part.clear();
      map.knots(map.length() - pixel, map.length() + pixel, part);
      REQUIRE(part.size() == 2);
      CHECK(part[1] == Approx(map.length() + pixel / 2));
    }
  }
}
