#pragma once
// The independent judge of gc-shape vase --mesh: the G-code replayed
// through MachineState and measured against sections of the test mesh cut
// here, by brute force over its triangles (nothing of the library's STL
// reader, slicer, offsets or path: a segment per straddling triangle, an
// even-odd count for inside, the nearest segment for the distance).
//   wall    every sample (each 0.2 mm of every piece) inside the section at
//           the middle of its bead (z - pitch / 2) and half a line width
//           from its outline; Z never falls; no travel, no retraction, no
//           Z-only move; filament per mm of each turn after the ramp = line
//           width x pitch / filament area; the last Z at the model's top;
//   bottom  points of the first section (inside, at least a line width
//           from its outline) near a bead of the first layer.
#include <cstddef>
#include <string>

#include "mesh_maker.hpp"

namespace meshtest {

struct VaseSetup {
  double scale = 1, center_x = 110, center_y = 110;
  double layer_height = 0.3, line_width = 0.5, filament_diameter = 1.75;
  int bottom_layers = 3;
};

struct VaseCheck {
  int layers = 0;                  // layer markers seen
  int turns = 0;                   // expected turns of the wall
  std::size_t wall_samples = 0;
  std::size_t outside = 0;         // wall samples outside their section
  double worst_offset = 0;         // mm, largest |distance from the outline - line width / 2|
  double worst_at[3] = {0, 0, 0};  // where
  double z_fall = 0;               // mm, largest drop of Z along the wall
  std::size_t other_moves = 0;     // travels, retractions, Z-only moves in the wall
  double worst_flow = 0;           // largest |filament per mm / expected - 1| of a turn after the ramp
  double wall_top = 0, model_top = 0;
  std::size_t bottom_points = 0;   // first-section points judged
  double bottom_gap = 0;           // mm, largest distance of one from a first-layer bead's centre line
  double bottom_far = 0;           // share of them farther than half a line width + 0.05 mm
};

VaseCheck check_vase(const std::string& gcode, const TestMesh& mesh, const VaseSetup& setup = {});

}  // namespace meshtest
