#pragma once
// The Proof checks of a generated lithophane, shared by the library's tests
// and gc-litho's tool tests: each layer's deposited volume against the band's
// area integrated independently from the height map, gaps between beads on
// rays across the band, and the extruder rate of unclamped fill pieces, all
// from the G-code as MachineState replays it (litho_support.hpp). Compiled
// once into the test kit (litho_check.cpp).
#include <cstddef>
#include <numbers>
#include <string>
#include <vector>

#include "gcode/litho/lithophane.hpp"
#include "gcode/litho/height_map.hpp"
#include "litho_support.hpp"

namespace littest {

using gcode::litho::HeightMap;
using gcode::litho::LithoOptions;
using gcode::litho::LithophanePlanner;

inline constexpr double kFilamentArea = std::numbers::pi * 0.875 * 0.875;

// What the printed layer should hold: the band's area (independently
// integrated from the height map, 0.005 mm steps) times the layer height.
double band_volume(const HeightMap& map, double sample_z, double layer_height);

// Coverage along one ray across the band, from the beads as the G-code
// describes them: each bead is a strip of width E x filament area /
// (length x layer height) around its segment; where it crosses the ray at
// an angle its extent along the ray is width / sin(angle). Gaps between
// beads are one thing; where the outermost beads end against the band's
// true surface is another (the surface is sampled every `resolution` mm, so
// between samples it is a chord of the picture's curve).
struct Coverage {
  double max_gap = 0;      // widest uncovered stretch between beads
  double surface = 0;      // largest distance between the covered span's ends and the band's ends
};

Coverage coverage(const std::vector<Bead>& beads, double ox, double oy, double ux, double uy, double lo, double hi,
                  double layer_height);

struct Measured {
  double worst_volume_error = 0;  // relative, over all layers
  double total_volume = 0;        // mm3 deposited in all layers
  double expected_volume = 0;     // mm3 of the height map's band over all layers
  double worst_gap = 0;           // mm
  double worst_surface = 0;       // mm
  double worst_rate_error = 0;    // relative, over unclamped fill pieces above the first layer
  std::size_t rate_pieces = 0;    // readings of the rate: pieces, the shortest read together (litho_check.cpp)
  std::size_t layers = 0;
};

// Every check of the Proof section on one generated lithophane.
Measured measure(const HeightMap& map, const LithophanePlanner& planner, const std::string& text, double gap_step);

}  // namespace littest
