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
#include <string_view>

#include "gcode/core/line.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/machine_state.hpp"

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

// Where the output text goes (an OutputBuffer in a tool, a string in tests).
class TextSink {
 public:
  virtual ~TextSink() = default;
  virtual void write(std::string_view bytes) = 0;
};

struct SubdivideStats {
  std::uint64_t lines = 0;        // input lines
  std::uint64_t moves_split = 0;  // input moves replaced by pieces
  std::uint64_t pieces = 0;       // pieces written for them
  std::uint64_t arcs = 0;         // arcs linearised
};

class Subdivider {
 public:
  // `diagnostics` may be null (no warnings).
  Subdivider(const SubdivideOptions& options, TextSink& out, Diagnostics* diagnostics);

  // One input line, after MachineState::apply: `move` is what it did and
  // `after` the state after it. `selected`: whether the line lies where the
  // user wants splitting (layer, height and feature filters).
  void process(const RawLine& raw, const Line& line, const Move& move, const MachineState& after,
               bool selected = true);

  const SubdivideStats& stats() const { return stats_; }

 private:
  struct Plan;
  bool plan_move(const RawLine& raw, const Line& line, const Move& move, const MachineState& after,
                 Plan& plan);
  void write_pieces(const RawLine& raw, const Line& line, const Plan& plan);
  void warn(std::uint64_t line_number, std::string_view message);

  SubdivideOptions options_;
  TextSink& out_;
  Diagnostics* diagnostics_;
  Precision precision_;
  SubdivideStats stats_;
  bool warned_rate_ = false;
  std::string_view ending_ = "\n";  // the input's line ending ("\n" or "\r\n"), static text
};

}  // namespace gcode
