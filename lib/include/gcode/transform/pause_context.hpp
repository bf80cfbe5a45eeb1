#pragma once
// The pause rules every pausing stream shares (gc-pause-at writes pauses
// into a file, gc-send pauses a live print): what has to be known about the
// print so far, and where the head may wait.
//
//   PauseContext  observes every line: what the file itself has retracted,
//                 the highest Z printed, the XY extent of what was printed,
//                 and the settings a seam carries (gc-send's live swap joins
//                 another file where the print stands).
//   ParkRules     where to park: --park X,Y, else the back of the bed (bed
//                 depth - 10 mm) centred on the print (background.md §1: the
//                 top layer stays visible and reachable); a park position above
//                 the print is refused when filament would be pushed there.
#include <string>

#include "gcode/core/geometry.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/core/print_area.hpp"
#include "gcode/pipeline/stage.hpp"
#include "gcode/transform/pause_sequence.hpp"
#include "gcode/transform/stream_tracker.hpp"

namespace gcode {

class PauseContext {
 public:
  // Call with every line of the stream, in order.
  void observe(const TrackedLine& t) { stream_.observe(t); }

  double top_z() const { return stream_.top_z; }
  // XY extent of the extrusions inside layers (empty before the first).
  const Box2& printed() const { return stream_.extent; }
  double pending_retraction() const { return stream_.retracted; }
  // Where printing stops, for build_pause().
  PausePoint point(const MachineState& state, const Precision* precision) const {
    return PausePoint{state, stream_.retracted, stream_.top_z, precision};
  }
  // The printed side of a seam (seam.hpp) with the printer in `state`.
  StreamPoint stream_point(const MachineState& state) const {
    StreamPoint p = stream_;
    p.state = state;
    return p;
  }

 private:
  StreamPoint stream_;  // its state is not kept: the caller has the printer's
};

struct ParkRules {
  bool given = false;      // --park X,Y
  double x = 0, y = 0;
  PrintArea area;          // what the file says: bed, height, the print's box

  // Throws std::runtime_error when the park position is unknown (no --park,
  // and the file does not say how big the bed is).
  void check() const;
  // The print's XY extent as far as known: the slicer's box and what was printed.
  Box2 print_box(const PauseContext& context) const;
  // Sets config.park_x/park_y for a pause now. Throws std::runtime_error when
  // the block pushes filament (reload, purge, prime) with the head above the
  // print: the blob would land on it.
  void place(const PauseContext& context, const Precision& precision, PauseConfig& config) const;
  // A live pause (gc-send) never stays on the part: with a park position,
  // place(); without one, config.park = false (retract and lift where the
  // head is) and no filament pushed there (reload, purge and prime left out).
  // Returns what could not be done, for a warning; empty when parked.
  std::string place_or_lift(const PauseContext& context, const Precision& precision, PauseConfig& config) const;
};

}  // namespace gcode
