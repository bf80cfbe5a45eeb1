#pragma once
// One way from one machine state to another: the lines that take a printer
// from how it stands ("from") to how a stream expects it ("to") without
// touching the part. Every inserted block that puts a machine back goes
// through it: the seam of a splice (seam.hpp), the bridge over left-out
// layers (layer_extract.hpp), the return of a pause (pause_sequence.hpp),
// gc-send's put-back after commands typed while paused, and a resume after
// a printer reset.
//
// A Transition follows every line it writes through a MachineState, so it
// always knows the printer as its lines leave it (printer()): the modes, the
// position and which axes are known, the E coordinate, F, firmware
// retraction, heaters and fan. Its steps write a line only where the
// printer differs from what is asked, and callers compose them in the order
// their block needs (each existing block keeps its own order and output).
// between() is the whole way in the order a printer wants it after a reset:
//
//   1. heaters, bed first, waited for where they rise (a printer reset or
//      cold, the part must stay stuck and nothing may move cold);
//   2. absolute positioning for the moves (G90);
//   3. where the position is unknown: G28 X Y (never Z: the part is under
//      the nozzle) and G92 Z at the height the caller says the nozzle is;
//   4. the tool; lift above everything printed; travel; descend;
//   5. firmware retraction and E to the target's retraction state (and a
//      prime where asked);
//   6. G91, M82/M83 (the target's, where it set one), the E coordinate
//      (G92 E), the feed rate, the fan, the speed and flow factors
//      (M220/M221).
//
// Numbers: positions the target is at are written back exactly; heights the
// transition makes up are rounded to the input's Z decimals; E moves are
// written at the input's E decimals, in the printer's E mode, in pieces
// the firmware accepts (kMaxExtrudeChunk).
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/fixed.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/core/machine_state.hpp"

namespace gcode {

// Firmware refuses single extrusions longer than EXTRUDE_MAXLENGTH (200 mm in
// Marlin's defaults, "prevent lengthy extrude"); long E moves go in chunks.
inline constexpr double kMaxExtrudeChunk = 150;

// Speeds and heights of a transition's moves.
struct TransitionMoves {
  double lift = 1;            // mm above the highest of the heights that count
  double max_z = 0;           // the printer's height limit; 0 = unknown
  double z_feed = 600;        // mm/min for the lift and the way down
  double xy_feed = 3000;      // mm/min for the travel
  double e_feed = 2100;       // mm/min for retraction and unretraction
  bool g0 = true;             // travel with G0 (false: G1)
};

class Transition {
 public:
  // `from`: the printer as it stands (a reset printer: a default MachineState,
  // nothing known). `precision`: the input's decimals. Lines go to `out`.
  Transition(const MachineState& from, const Precision& precision, std::vector<std::string>& out,
             TransitionMoves moves = {});

  // The printer as the lines written so far leave it.
  const MachineState& printer() const { return now_; }
  const TransitionMoves& moves() const { return moves_; }
  // Where the next lines go (a pause writes its two halves apart).
  void write_to(std::vector<std::string>& out) { out_ = &out; }
  // What the E moves pushed in total (mm; negative: retracted).
  Fixed net_filament() const { return net_; }

  // Any line, followed like the others.
  void line(std::string_view text);
  // A line the transition does not follow (the user's own, a firmware's
  // pause routine): it is written, the printer is taken to be as it was.
  void opaque(std::string_view text) { out_->emplace_back(text); }

  // --- Modes. Each writes only where the printer differs, unless forced.
  void positioning(bool relative);                  // G90 / G91
  void e_mode(bool relative, bool force = false);   // M82 / M83
  void e_coordinate(Fixed e, bool force = false);   // G92 E
  void feed_rate(double mm_min, bool force = false);  // G1 F (nothing for 0)
  void firmware_retraction(bool retracted);         // G10 / G11
  void tool(int tool);                              // T<n>

  // --- Moves, at the transition's speeds.
  void move_z(Fixed z);                     // G0/G1 Z, when not there
  void move_xy(Fixed x, Fixed y);           // G0/G1 X Y, always
  void home_xy();                           // G28 X Y
  void declare_z(Fixed z);                  // G92 Z: the nozzle stands at z
  // The height to travel at: `base` (the highest that counts) plus the lift,
  // at the input's Z decimals, within the printer's limit (so possibly
  // below `base`: each block says what it may not go under).
  Fixed safe_z(Fixed base) const;
  // E moves of `amount` mm (negative: retract), in the printer's E mode and
  // coordinate, at the input's E decimals, in firmware-sized pieces.
  void extrude(Fixed amount, double feed_mm_min);
  void extrude_mm(double amount_mm, double speed_mm_s);  // rounded first

  // --- Heaters and fan (the numbers MachineState keeps).
  // `wait`: M109/M190 (R when cooling: Marlin's S waits only while heating).
  // `name_tool`: the line names the tool (another than the active one, or
  // one of several heaters set together).
  void hotend(int tool, double target, bool wait, bool name_tool);
  void bed(double target, bool wait);
  void fan(double speed);
  // Heaters to `to`'s targets where they differ: bed first, then the
  // hotends; waited for where `wait_rising` and they rise.
  void heaters(const MachineState& to, bool wait_rising);
  void speed_factor(double percent);   // M220 S
  void flow_factor(double percent);    // M221 S

  // The whole way to `to` (see the header comment). `top_z`: the highest Z
  // printed, the travel clears it. `nozzle_z`: where the nozzle stands when
  // the printer does not know its Z (after a reset; NaN: unknown, which is
  // an error). `retracted_from`/`retracted_to`: mm the E moves of each side
  // have retracted and not pushed back; `prime`: mm pushed at the target
  // before its own retraction state is taken.
  struct Between {
    double top_z = 0;
    double nozzle_z = std::numeric_limits<double>::quiet_NaN();
    double retracted_from = 0;
    double retracted_to = 0;
    double prime = 0;
  };
  // Throws std::invalid_argument when the way cannot be known (inches on
  // either side, the target's position unknown, the nozzle's Z unknown).
  void between(const MachineState& to, const Between& how);

 private:
  void move(char axis1, Fixed v1, char axis2, Fixed v2, bool two, double feed);

  MachineState now_;
  const Precision& precision_;
  std::vector<std::string>* out_;
  TransitionMoves moves_;
  Fixed net_;
  LineBuilder b_;
};

}  // namespace gcode
