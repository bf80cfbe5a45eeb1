#pragma once
// Shared by the gc-litho unit tests: generated pictures, and G-code read back
// through the library's own MachineState (not through anything gc-litho
// wrote), as beads with their layer, feature type, width and speed.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/litho/height_map.hpp"
#include "gcode/litho/image.hpp"

namespace littest {

// A flat plate `width` mm wide, the rest as HeightMapOptions has it.
inline gcode::litho::HeightMapOptions plate(double width) {
  gcode::litho::HeightMapOptions o;
  o.width = width;
  return o;
}

// Luma from 0 at the left to 255 at the right (or top to bottom).
inline gcode::litho::GreyImage gradient(int width, int height, bool vertical = false) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int along = vertical ? y : x;
      const int n = vertical ? height : width;
      px[static_cast<std::size_t>(y * width + x)] = static_cast<std::uint8_t>(std::lround(255.0 * along / (n - 1)));
    }
  return {width, height, std::move(px)};
}

// Black text-like strokes on white: bars and a ring, hard edges everywhere.
inline gcode::litho::GreyImage strokes(int width, int height) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 255);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double dx = x - width * 0.7, dy = y - height * 0.5;
      const double r = std::sqrt(dx * dx + dy * dy);
      const bool bar = (x / 6) % 3 == 0 && y > height / 5 && y < height * 4 / 5 && x < width / 2;
      const bool ring = r > height * 0.2 && r < height * 0.3;
      if (bar || ring) px[static_cast<std::size_t>(y * width + x)] = 0;
    }
  return {width, height, std::move(px)};
}

// Binary PGM (P5) bytes of a picture.
inline std::string pgm(const gcode::litho::GreyImage& image) {
  std::string out = "P5\n" + std::to_string(image.width()) + " " + std::to_string(image.height()) + "\n255\n";
  out.append(reinterpret_cast<const char*>(image.pixels().data()), image.pixels().size());
  return out;
}

enum class Role { Outer, Inner, Fill, Other };

struct Bead {
  double x0, y0, x1, y1;
  double filament;  // mm of filament
  double feed;      // mm/min
  double length;    // mm
  Role role;
  int layer;
  double z;
};

struct Replayed {
  std::vector<Bead> beads;        // extruding moves inside ;LAYER: sections
  std::vector<double> layer_z;    // Z of each layer's beads
  int layer_markers = 0;
  int layer_count_header = -1;
  double filament_outside_layers = 0;  // purge line, retractions that were not undone
  std::size_t retractions = 0;
};

inline Replayed replay(std::string_view text) {
  Replayed r;
  gcode::MachineState state;
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  int layer = -1;
  Role role = Role::Other;
  while (split.next(raw)) {
    const gcode::Line line = gcode::Line::parse(raw.text);
    const std::string_view t = raw.text;
    if (t.starts_with(";LAYER:")) {
      layer = std::stoi(std::string(t.substr(7)));
      ++r.layer_markers;
      role = Role::Other;
    } else if (t.starts_with(";LAYER_COUNT:")) {
      r.layer_count_header = std::stoi(std::string(t.substr(13)));
    } else if (t == ";TYPE:WALL-OUTER") {
      role = Role::Outer;
    } else if (t == ";TYPE:WALL-INNER") {
      role = Role::Inner;
    } else if (t == ";TYPE:FILL") {
      role = Role::Fill;
    }
    const gcode::Move m = state.apply(line);
    if (m.retraction()) ++r.retractions;
    if (m.extruding && layer >= 0) {
      if (static_cast<int>(r.layer_z.size()) <= layer) r.layer_z.resize(static_cast<std::size_t>(layer) + 1, 0);
      r.layer_z[static_cast<std::size_t>(layer)] = m.end[gcode::kZ];
      r.beads.push_back({m.start[gcode::kX], m.start[gcode::kY], m.end[gcode::kX], m.end[gcode::kY], m.filament,
                         m.feedrate, m.length, role, layer, m.end[gcode::kZ]});
    } else if (m.filament != 0 && (layer < 0 || !m.moves_head())) {
      r.filament_outside_layers += m.filament;
    }
  }
  return r;
}

}  // namespace littest
