#pragma once
// Keeps the start code, a chosen set of layers and the end code, as G-code a
// printer can run: where layers are left out, a short bridge keeps the E
// coordinate continuous (G92 E in absolute mode), restores the firmware
// retraction, the G90/G91 and M82/M83 modes, the temperatures and the fan
// the left-out layers set, and travels safely into the next chosen layer
// (lift above both heights, move in XY, go down to the layer's Z, restore
// the feed rate). With every layer chosen nothing is inserted, so the output
// is the input byte for byte.
#include <functional>
#include <string>

#include "gcode/core/line_builder.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gcode {

struct ExtractOptions {
  double lift_mm = 1.0;             // clearance above the higher of the two Z
  double travel_feedrate = 3000;    // mm/min for the bridge's moves
  double z_feedrate = 600;
  std::string note_prefix;          // starts the bridge's comment ("gc-layers: ")
};

class LayerExtractor : public Stage {
 public:
  using Selector = std::function<bool(const LayerInfo&)>;
  // `precision`: the input's decimals (Pipeline::precision) for the bridge.
  LayerExtractor(Selector selected, const Precision& precision, ExtractOptions options = {});

  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) override;
  void line(const TrackedLine& t, Emitter& out) override;

  int layers_written() const { return written_; }

 private:
  void write_bridge(const MachineState& target, bool travel, Emitter& out);

  Selector selected_;
  const Precision& precision_;
  ExtractOptions options_;
  bool keep_ = true;
  bool skipped_ = false;     // layers were left out since the last written line
  int first_skipped_ = 0;
  int last_skipped_ = 0;
  int written_ = 0;
  // What the printer has been told when a run of left-out layers began.
  MachineState printed_;
};

}  // namespace gcode
