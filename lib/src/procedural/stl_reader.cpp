#include "gcode/procedural/stl_reader.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "gcode/core/number.hpp"

namespace gcode::procedural {

namespace {

constexpr std::size_t kHeader = 84;  // 80 bytes of text, the triangle count
constexpr std::size_t kFacet = 50;   // normal, three corners (12 floats), 2 bytes of attributes

std::uint32_t count_of(std::string_view bytes) {
  std::uint32_t n = 0;
  for (int i = 3; i >= 0; --i) n = (n << 8) | static_cast<unsigned char>(bytes[80 + i]);
  return n;
}

float float_at(const char* p) {
  // STL is little-endian, as is every machine this builds for.
  float f = 0;
  std::memcpy(&f, p, sizeof f);
  return f;
}

bool is_binary(std::string_view bytes) {
  return bytes.size() >= kHeader && bytes.size() == kHeader + kFacet * static_cast<std::uint64_t>(count_of(bytes));
}

Mesh read_binary(std::string_view bytes, std::string_view name, double merge) {
  const std::uint32_t n = count_of(bytes);
  MeshBuilder builder(merge);
  builder.reserve(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const char* facet = bytes.data() + kHeader + kFacet * t + 12;  // past the normal
    Vec3 c[3];
    for (int k = 0; k < 3; ++k) {
      const double x = float_at(facet + 12 * k), y = float_at(facet + 12 * k + 4), z = float_at(facet + 12 * k + 8);
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        throw MeshError(fmt::format("{}: triangle {}: a corner is not a finite number", name, t + 1));
      c[k] = {x, y, z};
    }
    builder.add_triangle(c[0], c[1], c[2]);
  }
  return builder.take();
}

// The words of an ASCII STL, with the line each is on.
class Words {
 public:
  explicit Words(std::string_view text) : text_(text) {}
  bool next(std::string_view& word) {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) {
      if (text_[at_] == '\n') ++line_;
      ++at_;
    }
    if (at_ >= text_.size()) return false;
    const std::size_t from = at_;
    while (at_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
    word = text_.substr(from, at_ - from);
    return true;
  }
  void skip_line() {
    while (at_ < text_.size() && text_[at_] != '\n') ++at_;
  }
  int line() const { return line_; }

 private:
  std::string_view text_;
  std::size_t at_ = 0;
  int line_ = 1;
};

Mesh read_ascii(std::string_view text, std::string_view name, double merge) {
  Words words(text);
  std::string_view w;
  words.next(w);  // "solid"
  words.skip_line();  // its name
  MeshBuilder builder(merge);
  auto fail = [&](std::string_view what) {
    return MeshError(fmt::format("{}: line {}: {}", name, words.line(), what));
  };
  auto next = [&] {
    if (!words.next(w)) throw MeshError(fmt::format("{}: the file ends inside a facet (truncated?)", name));
  };
  auto expect = [&](std::string_view word) {
    next();
    if (w != word) throw fail(fmt::format("expected '{}', not '{}'", word, w));
  };
  while (words.next(w)) {
    if (w == "endsolid") break;
    if (w != "facet") throw fail(fmt::format("expected 'facet' or 'endsolid', not '{}'", w));
    words.skip_line();  // "normal nx ny nz": not trusted
    expect("outer");
    expect("loop");
    Vec3 c[3];
    for (Vec3& v : c) {
      expect("vertex");
      double xyz[3];
      for (double& d : xyz) {
        next();
        if (!parse_number(w, d)) throw fail(fmt::format("expected a number, not '{}'", w));
        if (!std::isfinite(d)) throw fail(fmt::format("'{}' is not a finite number", w));
      }
      v = {xyz[0], xyz[1], xyz[2]};
    }
    expect("endloop");
    expect("endfacet");
    builder.add_triangle(c[0], c[1], c[2]);
  }
  if (w != "endsolid") throw fail("the file ends inside the solid (no 'endsolid')");
  return builder.take();
}

// ASCII: begins with "solid" and has no NUL byte near the start (a
// binary file's triangle count, after its "solid ..." header, has some).
bool is_ascii(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
  return bytes.substr(i, 5) == "solid" && bytes.substr(0, 1024).find('\0') == std::string_view::npos;
}

}  // namespace

Mesh read_stl(std::string_view bytes, std::string_view name, double merge_distance) {
  Mesh mesh;
  if (is_binary(bytes)) {
    mesh = read_binary(bytes, name, merge_distance);
  } else if (is_ascii(bytes)) {
    mesh = read_ascii(bytes, name, merge_distance);
  } else if (bytes.size() >= kHeader) {
    throw MeshError(fmt::format("{}: a binary STL counting {} triangles has {} bytes, this one {} (truncated, or not "
                                "an STL)",
                                name, count_of(bytes), kHeader + kFacet * std::uint64_t{count_of(bytes)}, bytes.size()));
  } else {
    throw MeshError(fmt::format("{}: not an STL file ({} bytes)", name, bytes.size()));
  }
  if (mesh.triangles.empty()) throw MeshError(fmt::format("{}: no triangles (an empty mesh)", name));
  return mesh;
}

}  // namespace gcode::procedural
