#pragma once
// Changes print speed inside a region and restores it after, exactly.
//
// F is modal: a move without an F word runs at the last F written. A tool
// that only rewrites the F words it sees (Cura's ChangeAtZ) leaves moves that
// inherit F at the old speed, and one that only scales at the region start
// leaves the moves after it at the new speed. Here every move gets the speed
// it should have, whatever lines carry F:
//
//   - each move in the region that is to change (extruding moves; travel too
//     when asked) runs at its original effective F times the factor, capped;
//   - every other move runs at exactly its original effective F.
//
// The stage keeps the feed rate of its output beside the input's and writes
// an F only where the two would differ for a move: on the first changed move
// of a region (even if that line had no F: the current F re-emitted scaled),
// on every line inside that carries an F (scaled), and on the first move
// after the region (the original modal F re-established). Positions, E and
// every other line stay byte for byte; an edited line gets a short comment
// ("; gc-speedup x3", "; gc-speedup restore").
//
// The stage can be switched on and off at any line (gc-send rushes the rest
// of a layer: on at the user's request, off at the layer's end). Switched
// off while the output runs at a changed speed, it stays on until the next
// move has its original F back, then switches itself off.
//
// The M220 route (options.m220) leaves F alone and inserts M220 S<percent>
// before the first move of the region and the restore before the first move
// after it: the firmware then scales every move, travel and retraction too.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/fixed.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/pipeline/selection.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gcode {

class Diagnostics;

// How the M220 route puts the firmware's factor back at the region's end.
enum class M220Restore : std::uint8_t {
  Reset,   // M220 S100
  Backup,  // M220 B at the start, M220 R at the end (Marlin 2, Prusa firmware)
};

// --m220-restore auto: the restore the firmware a file names (its slicer's
// flavor) is known to take. M220 B/R where it says Marlin 2 (Marlin 2 and
// Prusa firmware back the factor up); elsewhere B and R may be ignored, which
// would leave the printer at the changed speed, so M220 S100.
M220Restore m220_restore_for_flavor(std::string_view flavor);

struct SpeedOptions {
  // The change, one of: a factor; an absolute speed for every changed move;
  // a factor going linearly from ramp_first on the first layer of
  // ramp_layers to ramp_last on its last.
  double factor = 1;
  double speed = 0;                // mm/s; 0 = use the factor
  bool ramp = false;
  double ramp_first = 1;
  double ramp_last = 1;
  std::vector<int> ramp_layers;    // the region's layers, ascending

  // What changes besides extruding moves. Retraction and unretraction (also
  // while moving: wipes), Z moves (layer changes, Z-hops) never change.
  bool travel = false;             // travel in XY, changed like extrusion
  double travel_factor = 0;        // travel in XY by this factor instead; 0 = unused

  // Caps on changed moves; 0 = none. A cap never turns a speed-up into a
  // slow-down (or the other way): a move already beyond it keeps its speed.
  double max_speed = 0;            // mm/s
  double min_speed = 0;            // mm/s
  double max_flow = 0;             // mm^3/s of filament: filament per mm x area x speed
  double filament_diameter = 1.75; // mm

  bool m220 = false;               // the firmware's factor instead of F words
  M220Restore m220_restore = M220Restore::Reset;

  // The comment on every edited line ("" = none). Lines of the region that
  // already carry it (an earlier run) are refused unless `force`.
  std::string mark = "gc-speedup";
  bool force = false;

  // Throws std::invalid_argument naming the option that makes no sense.
  void validate() const;
};

struct SpeedStats {
  std::uint64_t moves_changed = 0;   // moves that run at a new speed
  std::uint64_t lines_edited = 0;    // lines whose F was written or changed
  std::uint64_t restores = 0;        // lines edited to put the original F back
  std::uint64_t capped_max_speed = 0;
  std::uint64_t capped_min_speed = 0;
  std::uint64_t capped_flow = 0;
  std::uint64_t m220_lines = 0;      // M220 lines inserted
  std::uint64_t left_alone = 0;      // moves of the region that could not be edited (N/checksum, odd F)
  std::vector<int> layers;           // the layers in which a move changed, ascending
  std::uint64_t capped() const { return capped_max_speed + capped_min_speed + capped_flow; }
};

class SpeedStage : public Stage {
 public:
  // `precision`: the input's decimals per letter (Pipeline::precision); F is
  // written with the decimals the input uses. `selection` (optional) is the
  // region: without one, every line while the stage is on; with one that
  // names nothing, every layer (start and end code are the printer's own).
  // `diagnostics` may be null.
  SpeedStage(const SpeedOptions& options, const Precision& precision, Diagnostics* diagnostics = nullptr,
             LayerSelection* selection = nullptr);

  void line(const TrackedLine& t, Emitter& out) override;
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) override;
  void finish(Emitter& out) override;
  // Off: the region ends here; the stage stays on until the next move has
  // its original speed back (or the firmware factor is restored).
  void set_enabled(bool on) override;

  // A new factor from the next move on (gc-send's `speed F`).
  void change_factor(double factor) { set_factor(Fixed::from_double(factor)); }
  // Whether the output runs at another speed than the input right now.
  bool changing() const { return differs_ || m220_percent_ != 100; }
  const SpeedStats& stats() const { return stats_; }

 private:
  struct Target {
    Fixed word;         // the F to write, in the file's units
    double feed = 0;    // mm/min, as the machine state will read it
    bool changed = false;
    bool travel = false;
    std::uint64_t SpeedStats::*cap = nullptr;  // the cap that bound the move, if any
  };
  struct Cache {
    bool valid = false;
    bool inches = false;
    int decimals = 0;
    double feed = 0;
    Target target;
  };
  bool in_region(const TrackedLine& t);
  bool eligible(const Move& move) const;
  Target target_for(const TrackedLine& t);
  void feed_move(const TrackedLine& t, Emitter& out);
  void m220_move(const TrackedLine& t, Emitter& out);
  void check_mark(const TrackedLine& t);
  void set_factor(Fixed factor);
  const std::string& note_for(bool change, const Target& target) const;
  void count_layer(int layer);

  SpeedOptions options_;
  const Precision& precision_;
  Diagnostics* diagnostics_;
  LayerSelection* selection_;
  Fixed factor_;              // the factor in effect (the ramp's for this layer)
  Fixed travel_factor_;
  bool ramp_layer_ = false;   // the current layer is one of the ramp's
  bool stopping_ = false;     // switched off, not yet back in step
  bool differs_ = false;      // the output's modal F is not the input's
  double out_feed_ = 0;       // the output's modal F (mm/min) while differs_
  int m220_percent_ = 100;    // the firmware factor the output has set
  bool warned_edit_ = false;
  std::string note_;          // "gc-speedup x3"
  std::string note_capped_;   // "gc-speedup x3 capped"
  std::string note_restore_;  // "gc-speedup restore"
  std::string note_travel_;   // "gc-speedup x2" (--travel-factor)
  std::string note_travel_capped_;
  Cache cache_[2];            // the last target for extrusion [0] and travel [1]
  SpeedStats stats_;
};

}  // namespace gcode
