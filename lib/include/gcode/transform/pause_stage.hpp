#pragma once
// Pauses written into the stream at layer boundaries (gc-pause-at): after the
// last move of the previous layer, before the move to the next layer's Z, so
// the nozzle never starts the next layer first. The block itself comes from
// pause_sequence.hpp, the park position from pause_context.hpp.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/layer_range.hpp"
#include "gcode/pipeline/stage.hpp"
#include "gcode/transform/pause_context.hpp"

namespace gcode {

// Where to pause; the rules combine.
class PauseTriggers {
 public:
  std::optional<LayerRange> before;  // before these layers print
  std::optional<LayerRange> after;   // once these layers are printed (N: before N+1)
  std::vector<double> heights;       // before the first layer above each height
  int every = 0;                     // before layers N+1, 2N+1, ...

  bool any() const { return before || after || !heights.empty() || every > 0; }
  // Whether a pause goes before layer `index` at `z`. A Z-hop is no layer,
  // so only layer heights count (Cura's PauseAtHeight was fooled, Cura #10242).
  bool at_layer(int index, double z);
  // Whether a pause goes after the last layer (--after-layer naming it).
  bool after_last(int layers);
  // After the whole input: throws std::runtime_error naming the option that
  // asked for a layer or height the file does not have.
  void verify(int layers, double top_layer_z) const;
  // Before it: a height at or above the print's top (Cura writes it in its
  // header) is refused at once. Throws std::runtime_error.
  void check_heights(const PrintArea& area) const;

 private:
  std::vector<bool> height_used_;
  int fired_before_ = 0, fired_after_ = 0, fired_every_ = 0;
};

// One pause as placed (for --dry-run and messages).
struct PlacedPause {
  int layer = 0;               // the layer it comes before; 0 after the last layer
  double z = 0;                // that layer's Z
  std::uint64_t line = 0;      // the input line where the layer begins
  double park_x = 0, park_y = 0, park_z = 0;
};

// The --dry-run table: "# layer\tz\tline\tpark" and a row per pause.
std::string pause_table(const std::vector<PlacedPause>& pauses);

class PauseStage : public Stage {
 public:
  // `note_prefix` starts the block's comments ("gc-pause-at: "); messages
  // and custom text in `config` may hold {layer} and {z}.
  PauseStage(PauseTriggers& triggers, ParkRules park, PauseConfig config, const Precision& precision,
             Diagnostics& diagnostics, std::string note_prefix);

  // Plans the pauses without writing blocks (--dry-run): see pauses().
  void set_dry_run(bool on) { dry_run_ = on; }

  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) override;
  void line(const TrackedLine& t, Emitter& out) override;

  const std::vector<PlacedPause>& pauses() const { return pauses_; }
  int layers() const { return layers_; }
  double top_layer_z() const { return top_layer_z_; }

 private:
  void pause(int layer, double z, std::uint64_t line, const MachineState& before, Emitter& out);

  PauseTriggers& triggers_;
  ParkRules park_;
  PauseConfig config_;
  const Precision& precision_;
  Diagnostics& diag_;
  std::string note_;
  PauseContext context_;
  std::vector<PlacedPause> pauses_;
  bool dry_run_ = false;
  int layers_ = 0;
  double top_layer_z_ = 0;
};

}  // namespace gcode
