#include "gcode/litho/image.hpp"

#include <stb_image.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include <fmt/format.h>

namespace gcode::litho {

namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

struct PixelsFree {
  void operator()(stbi_uc* p) const { stbi_image_free(p); }
};
using Pixels = std::unique_ptr<stbi_uc, PixelsFree>;

std::string reason() {
  const char* r = stbi_failure_reason();
  return r ? r : "unknown error";
}

// The checks every source shares once the header is known.
void check_size(const std::string& name, int width, int height, const ImageLimits& limits) {
  const auto pixels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  if (limits.max_pixels > 0 && pixels > limits.max_pixels)
    throw ImageError(fmt::format(
        "{}: {} x {} pixels is over the limit of {} megapixels (a lithophane needs about one pixel per "
        "0.1-0.2 mm); scale it down first, e.g. convert IMAGE -resize 2000x2000 small.png",
        name, width, height, static_cast<double>(limits.max_pixels) / 1e6));
  if (width < 2 || height < 2)
    throw ImageError(fmt::format("{}: {} x {} pixels; a lithophane needs at least 2 x 2", name, width, height));
}

GreyImage to_grey(const std::string& name, stbi_uc* raw, int width, int height, int channels) {
  if (!raw) throw ImageError(fmt::format("{}: cannot decode the picture ({})", name, reason()));
  Pixels owned(raw);
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<std::uint8_t> luma(count);
  const stbi_uc* p = raw;
  switch (channels) {
    case 1:
      std::copy(p, p + count, luma.begin());
      break;
    case 2:  // grey + alpha
      for (std::size_t i = 0; i < count; ++i, p += 2) luma[i] = luma_of(p[0], p[0], p[0], p[1]);
      break;
    case 3:
      for (std::size_t i = 0; i < count; ++i, p += 3) luma[i] = luma_of(p[0], p[1], p[2]);
      break;
    case 4:
      for (std::size_t i = 0; i < count; ++i, p += 4) luma[i] = luma_of(p[0], p[1], p[2], p[3]);
      break;
    default:
      throw ImageError(fmt::format("{}: {} channels per pixel is not a picture format this reads", name, channels));
  }
  return GreyImage(width, height, std::move(luma));
}

}  // namespace

GreyImage::GreyImage(int width, int height, std::vector<std::uint8_t> luma)
    : width_(width), height_(height), luma_(std::move(luma)) {
  if (width <= 0 || height <= 0 ||
      luma_.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw std::invalid_argument("GreyImage: pixel count does not match width x height");
}

std::uint8_t luma_of(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t alpha) {
  // Rec. 601 in thousandths, rounded; then over white by alpha.
  const unsigned y = (299u * r + 587u * g + 114u * b + 500u) / 1000u;
  const unsigned over = (y * alpha + 255u * (255u - alpha) + 127u) / 255u;
  return static_cast<std::uint8_t>(over);
}

GreyImage load_image(const std::string& path, const ImageLimits& limits) {
  File f(std::fopen(path.c_str(), "rb"));
  if (!f) throw ImageError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  if (std::fseek(f.get(), 0, SEEK_END) != 0)
    throw ImageError(fmt::format("{}: cannot read: not a regular file", path));
  const long size = std::ftell(f.get());
  if (size < 0) throw ImageError(fmt::format("{}: cannot read: not a regular file", path));
  if (size == 0) throw ImageError(fmt::format("{}: empty file", path));
  std::rewind(f.get());

  int width = 0, height = 0, channels = 0;
  // stbi_info reads only the header and puts the file position back.
  if (!stbi_info_from_file(f.get(), &width, &height, &channels))
    throw ImageError(fmt::format("{}: not a picture this reads (PNG, JPEG, BMP, PGM/PPM, GIF, TGA): {}", path,
                                 reason()));
  check_size(path, width, height, limits);
  stbi_uc* raw = stbi_load_from_file(f.get(), &width, &height, &channels, 0);
  return to_grey(path, raw, width, height, channels);
}

GreyImage decode_image(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits) {
  if (bytes.empty()) throw ImageError(fmt::format("{}: empty file", name));
  if (bytes.size() > static_cast<std::size_t>(INT_MAX))
    throw ImageError(fmt::format("{}: over 2 GB of data; scale the picture down first", name));
  const int length = static_cast<int>(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels))
    throw ImageError(fmt::format("{}: not a picture this reads (PNG, JPEG, BMP, PGM/PPM, GIF, TGA): {}", name,
                                 reason()));
  check_size(name, width, height, limits);
  stbi_uc* raw = stbi_load_from_memory(bytes.data(), length, &width, &height, &channels, 0);
  return to_grey(name, raw, width, height, channels);
}

void ToneOptions::validate() const {
  if (!(gamma > 0) || !std::isfinite(gamma)) throw std::invalid_argument("--gamma must be a number above 0");
  if (!(contrast > 0) || !std::isfinite(contrast))
    throw std::invalid_argument("--contrast must be a number above 0");
}

ToneCurve::ToneCurve(const ToneOptions& options) {
  options.validate();
  for (std::size_t i = 0; i < table_.size(); ++i) {
    double light = std::pow(static_cast<double>(i) / 255.0, options.gamma);
    light = std::clamp(0.5 + (light - 0.5) * options.contrast, 0.0, 1.0);
    table_[i] = options.invert ? light : 1.0 - light;
  }
}

}  // namespace gcode::litho
