#pragma once
// How high the print already stands over each spot of the bed, so a
// deformation that would send the nozzle down into it is caught.
//
// The bed is cut into square cells; each keeps the highest Z extruded in it
// by the layers before the current one (what the nozzle of the current
// layer must stay above: the current layer's own beads do not count, a
// spiral's previous turn does, being the previous layer). Memory grows with
// the printed area, not the file.
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace gcode {

class PrintedHeight {
 public:
  explicit PrintedHeight(double cell = 0.5) : cell_(cell) {}

  // An extruded point of the current layer.
  void add(double x, double y, double z);
  // The current layer is done: its points now count.
  void next_layer();
  // The highest Z printed by earlier layers in the cell of (x, y), or
  // `none` where nothing was.
  double top(double x, double y, double none) const;

 private:
  std::uint64_t key(double x, double y) const;

  double cell_;
  std::unordered_map<std::uint64_t, float> top_;
  std::vector<std::pair<std::uint64_t, float>> layer_;
};

}  // namespace gcode
