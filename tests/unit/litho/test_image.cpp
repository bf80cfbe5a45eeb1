#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include "gcode/litho/image.hpp"
#include "litho_support.hpp"
#include "test_support.hpp"

using gcode::litho::decode_image;
using gcode::litho::GreyImage;
using gcode::litho::ImageError;
using gcode::litho::load_image;

namespace {

std::string image_fixture(const char* name) { return gctest::fixture_path(std::string("images/") + name); }

// The message of the ImageError that loading `path` throws ("" if none).
std::string load_error(const std::string& path, gcode::litho::ImageLimits limits = {}) {
  try {
    load_image(path, limits);
  } catch (const ImageError& e) {
    return e.what();
  }
  return "";
}

int expected_gradient(int x) { return static_cast<int>(std::lround(255.0 * x / 63)); }

}  // namespace

TEST_CASE("litho image: luma uses Rec 601 weights and puts transparency over white", "[litho][image]") {
  CHECK(gcode::litho::luma_of(255, 255, 255) == 255);
  CHECK(gcode::litho::luma_of(0, 0, 0) == 0);
  CHECK(gcode::litho::luma_of(255, 0, 0) == 76);   // 0.299 x 255
  CHECK(gcode::litho::luma_of(0, 255, 0) == 150);  // 0.587 x 255
  CHECK(gcode::litho::luma_of(0, 0, 255) == 29);   // 0.114 x 255
  CHECK(gcode::litho::luma_of(0, 0, 0, 0) == 255);
  CHECK(gcode::litho::luma_of(0, 0, 0, 128) == 127);
}

TEST_CASE("litho image: PGM PNG BMP and JPEG fixtures decode to the same grey gradient", "[litho][image]") {
  for (const char* name : {"gradient.pgm", "gradient.png", "gradient.bmp", "gradient.jpg"}) {
    INFO(name);
    const GreyImage image = load_image(image_fixture(name));
    REQUIRE(image.width() == 64);
    REQUIRE(image.height() == 32);
    // JPEG is lossy: within a few levels; the others are exact.
    const int tolerance = std::string(name).ends_with(".jpg") ? 4 : 0;
    for (int y : {0, 15, 31})
      for (int x = 0; x < 64; ++x) REQUIRE(std::abs(image.at(x, y) - expected_gradient(x)) <= tolerance);
  }
}

TEST_CASE("litho image: an RGBA PNG becomes luma with transparent pixels white", "[litho][image]") {
  const GreyImage image = load_image(image_fixture("colours.png"));
  REQUIRE(image.width() == 2);
  REQUIRE(image.height() == 2);
  CHECK(image.at(0, 0) == 76);
  CHECK(image.at(1, 0) == 150);
  CHECK(image.at(0, 1) == 29);
  CHECK(image.at(1, 1) == 255);
}

TEST_CASE("litho image: a picture in memory decodes like the file", "[litho][image]") {
  const GreyImage generated = littest::gradient(7, 5, true);
  const std::string bytes = littest::pgm(generated);
  const GreyImage decoded = decode_image(
      std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), "memory.pgm");
  CHECK(decoded.pixels() == generated.pixels());
}

TEST_CASE("litho image: unusable pictures fail with a message naming the file and the problem", "[litho][image]") {
  CHECK_THAT(load_error(image_fixture("missing.png")),
             Catch::Contains("missing.png") && Catch::Contains("cannot open") && Catch::Contains("No such file"));
  CHECK_THAT(load_error(image_fixture("empty.png")), Catch::Contains("empty.png: empty file"));
  CHECK_THAT(load_error(image_fixture("not_an_image.png")), Catch::Contains("not a picture this reads"));
  CHECK_THAT(load_error(image_fixture("one_pixel.pgm")), Catch::Contains("1 x 1 pixels") &&
                                                             Catch::Contains("at least 2 x 2"));
  CHECK_THAT(load_error(gctest::fixture_path("images")), Catch::Contains("images"));
  CHECK_THROWS_AS(decode_image({}, "nothing"), ImageError);
}

TEST_CASE("litho image: a 20000 x 20000 picture is refused from its header before any decoding", "[litho][image]") {
  // The fixture is a PGM header that claims 20000 x 20000, then 64 bytes.
  // stb_image would decode it (the missing rows read as zeros) into 400 MB
  // and the luma copy into 400 MB more, all touched: the peak resident size
  // would jump by 800 MB. Refused from the header, it does not move.
  rusage before{};
  getrusage(RUSAGE_SELF, &before);
  const std::string message = load_error(image_fixture("huge_header.pgm"));
  rusage after{};
  getrusage(RUSAGE_SELF, &after);
  CHECK_THAT(message, Catch::Contains("20000 x 20000 pixels is over the limit of 25 megapixels") &&
                          Catch::Contains("scale it down"));
  CHECK(after.ru_maxrss - before.ru_maxrss < 64 * 1024);  // KiB
}

TEST_CASE("litho image: a lower pixel limit refuses a picture just above it and takes one at it", "[litho][image]") {
  gcode::litho::ImageLimits limits;
  limits.max_pixels = 64 * 32;
  CHECK(load_image(image_fixture("gradient.png"), limits).width() == 64);
  limits.max_pixels = 64 * 32 - 1;
  CHECK_THAT(load_error(image_fixture("gradient.png"), limits), Catch::Contains("over the limit"));
}

TEST_CASE("litho image: GreyImage refuses a pixel count that does not match its size", "[litho][image]") {
  CHECK_THROWS_AS(GreyImage(2, 2, std::vector<std::uint8_t>(3)), std::invalid_argument);
  CHECK_THROWS_AS(GreyImage(0, 2, {}), std::invalid_argument);
}

TEST_CASE("litho image: the tone curve maps dark to thick and applies invert gamma and contrast", "[litho][image]") {
  using gcode::litho::ToneCurve;
  using gcode::litho::ToneOptions;
  const ToneCurve plain;
  CHECK(plain(0) == 1.0);
  CHECK(plain(255) == 0.0);
  CHECK(plain(51) == Approx(0.8));
  ToneOptions inv;
  inv.invert = true;
  CHECK(ToneCurve(inv)(0) == 0.0);
  CHECK(ToneCurve(inv)(255) == 1.0);
  ToneOptions g;
  g.gamma = 2;
  CHECK(ToneCurve(g)(128) == Approx(1 - std::pow(128 / 255.0, 2)));
  ToneOptions c;
  c.contrast = 2;
  CHECK(ToneCurve(c)(60) == 1.0);  // light 0.235 -> -0.03 after contrast, clipped to 0
  CHECK(ToneCurve(c)(128) == Approx(1 - (0.5 + (128 / 255.0 - 0.5) * 2)));
  ToneOptions bad;
  bad.gamma = 0;
  CHECK_THROWS_WITH(ToneCurve(bad), Catch::Contains("--gamma"));
  bad.gamma = 1;
  bad.contrast = -1;
  CHECK_THROWS_WITH(ToneCurve(bad), Catch::Contains("--contrast"));
}
