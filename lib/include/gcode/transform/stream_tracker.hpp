#pragma once
// The stream tracker: what a stream has done beyond its machine state, kept
// line by line, so that a pause, a seam or a resume knows how it stands.
//
//   RetractionTracker  the filament the stream's own E moves retracted and
//                      have not pushed back since the last extrusion (a wipe,
//                      moving while retracting, counts too);
//   StreamPoint        how a stream stands at one point: the machine state,
//                      that retraction, the carried settings (temperatures,
//                      fans, flow, pressure advance as the lines set them),
//                      whether the stream set its E mode itself, the highest
//                      Z extruded at and the XY extent of what was extruded
//                      in layers. observe() follows one line.
//
// Every stream that needs to know this follows it here: a pause's context
// (pause_context.hpp), the layer index of a file to splice in
// (layer_index.hpp), a splice's main stream and the blocks it prints
// (splice_stage.hpp, block_stream.hpp).
#include "gcode/core/geometry.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/transform/carried_settings.hpp"

namespace gcode {

class RetractionTracker {
 public:
  void observe(const Move& move) { pending_ = after(pending_, move); }
  double pending() const { return pending_; }

  // What is retracted after `move` when `pending` was before it.
  static double after(double pending, const Move& move) {
    if (move.extruding) return 0;
    if (move.kind != MoveKind::Linear && move.kind != MoveKind::Arc) return pending;
    pending -= move.filament;
    return pending < 0 ? 0 : pending;
  }

 private:
  double pending_ = 0;
};

struct StreamPoint {
  MachineState state;
  double retracted = 0;       // mm retracted with E moves and not pushed back (RetractionTracker)
  CarriedSettings settings;
  bool e_mode_set = false;    // the stream has set its E mode itself (M82/M83)
  double top_z = 0;           // printed side: the highest Z extruded at so far
  Box2 extent;                // printed side: XY extent of what was extruded in layers
  double layer_z = 0;         // block side: the Z of the layer that starts here

  // Follows what one line does to the stream beyond the machine state: the
  // retraction, the carried settings and the E mode. `tool` is the tool
  // active before it. Returns whether it set a carried setting.
  bool follow(const Line& line, const Move& move, int tool) {
    retracted = RetractionTracker::after(retracted, move);
    if (line.is_m(82) || line.is_m(83)) e_mode_set = true;
    return CarriedSettings::may_set(line) && settings.observe(line, tool);
  }
  // Follows what one move printed: the top Z (`z_shift`: the output's Z
  // minus the line's) and, inside layers, the XY extent.
  void printed(const Move& move, Region region, double z_shift = 0) {
    if (!move.extruding) return;
    if (move.end[kZ] + z_shift > top_z) top_z = move.end[kZ] + z_shift;
    if (region == Region::Layer) {
      extent.add(move.start[kX], move.start[kY]);
      extent.add(move.end[kX], move.end[kY]);
    }
  }
  // Both, for a line of a pipeline.
  void observe(const TrackedLine& t, double z_shift = 0) {
    follow(t.line, t.move, t.before.tool);
    printed(t.move, t.region, z_shift);
  }
};

}  // namespace gcode
