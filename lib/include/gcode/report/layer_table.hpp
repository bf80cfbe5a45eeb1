#pragma once
// Per-layer figures for gc-layers: where each layer lies in the file (lines
// and bytes), how much filament and path it holds, which features it prints,
// and totals for the whole print. A report stage: it passes every line on.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gcode/core/geometry.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gcode {

struct LayerRow {
  Region region = Region::StartCode;
  LayerInfo info;                  // index 0 for start and end code
  std::uint64_t first_line = 0;    // 0 when the region holds no line
  std::uint64_t last_line = 0;
  std::uint64_t byte_begin = 0;    // [begin, end)
  std::uint64_t byte_end = 0;
  double filament = 0;             // net mm of filament pushed (retractions subtract)
  double extruded = 0;             // mm pushed by extruding moves only
  double path = 0;                 // mm of extruding moves
  double travel = 0;               // mm of non-extruding head moves
  std::uint64_t moves = 0;
  std::vector<int> features;       // feature ids seen, in order of first use
};

class LayerTable : public Stage {
 public:
  LayerTable();
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) override;
  void line(const TrackedLine& t, Emitter& out) override;

  const std::vector<LayerRow>& layers() const { return layers_; }
  const LayerRow& start_code() const { return start_; }
  const LayerRow& end_code() const { return end_; }
  bool has_end_code() const { return has_end_; }
  const Box3& extrusion_bounds() const { return bounds_; }
  // Net filament over the whole file, start and end code included.
  double total_filament() const { return total_filament_; }
  // Filament pushed by extruding moves inside the layers: what slicers report
  // as "filament used" (Cura ;Filament used:, PrusaSlicer ; filament used [mm]).
  double layers_extruded() const;
  std::uint64_t total_lines() const { return total_lines_; }
  std::uint64_t total_bytes() const { return total_bytes_; }

 private:
  LayerRow& current();

  LayerRow start_;
  LayerRow end_;
  bool has_end_ = false;
  std::vector<LayerRow> layers_;
  Box3 bounds_;
  double total_filament_ = 0;
  std::uint64_t total_lines_ = 0;
  std::uint64_t total_bytes_ = 0;
};

// Filament mass in grams for a length in mm.
double filament_mass_g(double length_mm, double diameter_mm, double density_g_cm3);

}  // namespace gcode
