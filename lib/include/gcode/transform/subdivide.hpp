#pragma once
// Cuts long moves into short pieces so the printer's buffer holds only a few
// millimetres (or milliseconds) of motion.
//
// Why: firmware executes everything already queued before it reacts to
// anything new. 16 buffered moves of 100 mm at 30 mm/s delay a pause by 53 s;
// cut to 0.2 mm they delay it by 3.2 mm of travel (background.md §1).
//
// A move longer than the limit becomes n equal pieces, n = ceil(length / limit).
// What the pieces must keep exactly:
//   - absolute coordinates: the last piece ends on the input's own text for
//     every axis it wrote (X, Y, Z, E), so the file's state after the move is
//     bit-identical to the input's;
//   - relative E (M83, or G91) and G91 XYZ: the pieces are integer counts of
//     the written precision that sum exactly to the written amount (the
//     rounding remainder is carried, never dropped);
//   - F is modal: only the first piece carries the line's F, and its comment.
// The limit is reduced by the rounding of the written coordinates, so a
// piece is never longer than the limit once written, and a second run with
// the same limit changes nothing.
//
// G2/G3 arcs become G1 chords that respect both the limit and a deviation
// tolerance; E and Z are shared out along the arc length.
#include <cstdint>
#include <string>
#include <string_view>

#include "gcode/core/line.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/pipeline/selection.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gcode {

class Diagnostics;

struct SubdivideOptions {
  // Choose one limit: a fixed length, or a time budget for the whole buffer.
  double max_length = 0;     // mm per piece; 0 = not used
  double latency = 0;        // s of motion the buffer may hold; 0 = not used
  int buffer = 20;           // moves the firmware holds: 16 planner blocks + 4 queued commands
  double max_rate = 0;       // lines per second the link can carry; 0 = unlimited
  double min_length = 0.05;  // mm; the limit never drops below twice this
  bool split_travel = true;  // buffered travel delays a pause as much as printing does
  bool split_arcs = true;    // G2/G3 -> G1 chords
  double arc_tolerance = 0.01;  // mm a chord may deviate from its arc

  bool has_limit() const { return max_length > 0 || latency > 0; }
  // Throws std::invalid_argument naming the option that makes no sense.
  void validate() const;
  // The longest piece for a move at `feedrate` mm/min; 0 when no limit applies.
  // `rate_won` is set when --max-rate forced a longer piece than the limit.
  double piece_limit(double feedrate, bool* rate_won = nullptr) const;
};

struct SubdivideStats {
  std::uint64_t lines = 0;        // input lines
  std::uint64_t moves_split = 0;  // input moves replaced by pieces
  std::uint64_t pieces = 0;       // pieces written for them
  std::uint64_t arcs = 0;         // arcs linearised
};

// The pipeline stage: moves in the selection longer than the limit become
// pieces (the last one keeps the input line's ending), everything else
// passes on unchanged.
class Subdivider : public Stage {
 public:
  // `precision`: the input's decimals per letter (Pipeline::precision), at
  // least what pieces are written with. `selection` (optional) limits the
  // splitting to layers, heights and features. `diagnostics` may be null.
  Subdivider(const SubdivideOptions& options, const Precision& precision, Diagnostics* diagnostics,
             LayerSelection* selection = nullptr);

  void line(const TrackedLine& t, Emitter& out) override;
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) override;

  const SubdivideStats& stats() const { return stats_; }

 private:
  struct Plan;
  // A move's longest piece (mm) and whether --max-rate set it.
  struct PieceLimit {
    double mm = 0;
    bool rate_won = false;
  };
  // Whether a move is to be cut at all (the cheap checks, before a Plan).
  bool wants_cut(const TrackedLine& t, PieceLimit& limit) const;
  // plan_move's steps, in its order.
  bool plan_move(const TrackedLine& t, const PieceLimit& limit, Plan& plan);
  bool plan_axes(const TrackedLine& t, Plan& plan);
  bool plan_words(const TrackedLine& t, Plan& plan);
  int plan_decimals(const TrackedLine& t, Plan& plan) const;
  double plan_arc(const TrackedLine& t, Plan& plan, double limit, double effective);
  void warn_rate_once(const TrackedLine& t, double limit);
  void write_pieces(const TrackedLine& t, const Plan& plan, Emitter& out);
  void warn(std::uint64_t line_number, std::string_view message);

  SubdivideOptions options_;
  const Precision& precision_;
  Diagnostics* diagnostics_;
  LayerSelection* selection_;
  SubdivideStats stats_;
  bool warned_rate_ = false;
  std::string scratch_;  // the first piece with the input's comment
};

}  // namespace gcode
