#pragma once
// A picture as grey levels, and the tone curve that turns a grey level into
// the share of a lithophane's thickness range.
//
// Physics in two sentences: light through a lithophane falls off with the
// plastic's thickness, so a dark pixel becomes a thick spot and a light pixel
// a thin one. The picture is kept as 8-bit luma (Rec. 601, the weights JPEG
// uses); transparency is put over white (nothing there, so let light through).
//
// Decoding is stb_image (Debian's libstb-dev): PNG, JPEG, BMP, PGM/PPM, and
// also GIF, TGA, PSD, HDR. Memory is bounded before anything is decoded: the
// header gives the size, and a picture over `max_pixels` is refused with a
// message that says how to shrink it. A lithophane needs no more than one
// pixel per 0.1-0.2 mm (a 100 mm plate: 500-1000 pixels wide), so the default
// limit of 25 megapixels (a 6000 x 4000 camera photo) is generous; decoding
// one costs at most width x height x channels bytes plus the luma copy.
#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace gcode::litho {

// An image that cannot be used: unreadable, empty, not a picture, too small,
// too large. The message names the file and says what to do.
struct ImageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct ImageLimits {
  std::uint64_t max_pixels = 25'000'000;  // width x height, checked from the header
};

class GreyImage {
 public:
  GreyImage() = default;
  // `luma` holds width x height values, row by row from the top-left corner.
  // Throws std::invalid_argument when the sizes do not match or are not positive.
  GreyImage(int width, int height, std::vector<std::uint8_t> luma);

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return luma_.empty(); }
  // 0 = black, 255 = white. x from the left, y from the top.
  std::uint8_t at(int x, int y) const {
    return luma_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)];
  }
  const std::vector<std::uint8_t>& pixels() const { return luma_; }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> luma_;
};

// Reads a picture file. Throws ImageError for a file that cannot be opened,
// an empty file, data that no decoder recognises, a picture smaller than
// 2 x 2 pixels, or one over the pixel limit (refused from the header alone).
GreyImage load_image(const std::string& path, const ImageLimits& limits = {});
// The same for bytes already in memory (`name` is used in messages).
GreyImage decode_image(std::span<const std::uint8_t> bytes, const std::string& name,
                       const ImageLimits& limits = {});

// Luma of an RGB(A) pixel: Rec. 601 weights, alpha composited over white.
std::uint8_t luma_of(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t alpha = 255);

struct ToneOptions {
  bool invert = false;   // light = thick (for a negative, or a picture meant to be seen lit from the front)
  double gamma = 1.0;    // applied to luma (0..1) first: > 1 darkens the mid-tones, so they print thicker
  double contrast = 1.0; // then stretched about mid-grey and clipped: > 1 more contrast
  // Throws std::invalid_argument naming the option that makes no sense.
  void validate() const;
};

// Maps a luma value to the share of the thickness range, 0 (thinnest) to 1
// (thickest): luma -> ^gamma -> contrast about 0.5 -> darker = thicker
// unless inverted. A 256-entry table, so mapping a pixel costs one load.
class ToneCurve {
 public:
  explicit ToneCurve(const ToneOptions& options = {});
  double operator()(std::uint8_t luma) const { return table_[luma]; }

 private:
  std::array<double, 256> table_{};
};

}  // namespace gcode::litho
