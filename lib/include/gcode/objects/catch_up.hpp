#pragma once
// Back onto the input's path after lines were left out: before each further
// input line, the few lines that bring the printer to where that line
// expects it, only as far as the line depends on it, so the travel goes
// straight to what is printed next and not through what was left out.
//
// What a line depends on, and what is written before it:
//   - any motion: firmware retraction (G10/G11) as the input has it, and
//     the filament retracted further where the input is more retracted;
//   - a line with E in absolute E: the E coordinate (G92 E);
//   - an extrusion: the nozzle primed exactly as in the input (the
//     retraction depth of RetractionTracker), its start point (XY and Z;
//     up first where the input is higher, else across first);
//   - a move in XY that does not set both X and Y absolutely, an arc, or
//     any move in G91: the position; a move in XY without Z: the Z;
//   - a motion without F: the feed rate.
// Lines that leave the printer where the input stands (an absolute travel,
// a G92 E, a Z move) catch it up by themselves; once nothing differs the
// stream follows the input again and nothing more is written.
//
// Everything else (modes, temperatures, fans, tools, G92) the left-out
// lines carry is not left out (object_excluder.hpp keeps those lines), so
// it is as in the input.
#include <string>
#include <vector>

#include "gcode/core/line_builder.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/machine_state.hpp"

namespace gcode {

// A line that moves the head or the filament (G0-G3, G10/G11 firmware
// retraction): what a left-out block drops, and what catching up is for.
inline bool is_motion_line(const Move& m) {
  return m.kind == MoveKind::Linear || m.kind == MoveKind::Arc || m.kind == MoveKind::FirmwareRetract ||
         m.kind == MoveKind::FirmwareUnretract;
}

struct CatchUpMoves {
  double xy_feed = 6000;  // mm/min
  double z_feed = 600;
  double e_feed = 2100;
};

class StreamCatchUp {
 public:
  explicit StreamCatchUp(const Precision& precision, CatchUpMoves moves = {}) : precision_(precision), moves_(moves) {}
  // Lines are being left out; the printer stands in `printed` with
  // `retracted` mm retracted (if it was following the input until now).
  void leave(const MachineState& printed, double retracted);
  bool behind() const { return behind_; }
  // Before input line `t` goes out (`in_retracted`: the input's retraction
  // before it): the lines it needs, appended to `out`.
  void before(const TrackedLine& t, double in_retracted, std::vector<std::string>& out);
  // `t` went out; `in_retracted`: the input's retraction after it.
  void passed(const TrackedLine& t, double in_retracted);
  // Everything to `target` (the input's end): position, E, retraction, F.
  void all(const MachineState& target, double in_retracted, std::vector<std::string>& out);
  // The printer as the output leaves it (valid while behind()).
  const MachineState& printer() const { return printer_; }
  double retracted() const { return retracted_; }

 private:
  void check_caught_up(const MachineState& input, double in_retracted);
  const Precision& precision_;
  CatchUpMoves moves_;
  bool behind_ = false;
  MachineState printer_;
  double retracted_ = 0;
};

}  // namespace gcode
