#pragma once
// gc-relayer's rules as SplicePlans (splice.hpp): continue a print with a
// re-sliced file, and resume a failed print from a height.
//
// Joining (background.md §1): the old file is printed up to and including its
// last layer at or below the chosen height (the printed height P), then the
// new file from the layer whose Z - P lies in (0, its height + 0.01]. When the
// layer heights differ, the new file's layers rarely sit on P:
//
//   - a layer whose bottom lies below P (it overlaps what is printed) is left
//     out: "skip layers already covered";
//   - a layer whose bottom lies above P would leave a gap: the missing height
//     is printed first with that layer's paths at the intermediate Z, its
//     extrusion scaled to the real height: "go back and print missing layers".
//
// The new file's start code is left out except for what the seam carries
// (temperatures, fans, flow, pressure advance); its end code is kept.
//
// Resuming: the file's start code is left out and replaced by a resume
// sequence: heat the bed, then the nozzle, and wait; lift the nozzle off the
// part and declare Z (G92 Z: the nozzle stands where it stopped, at the
// measured height, plus the lift); home X and Y only (never Z with a part on
// the bed); optionally purge away from the part; then the file from its first
// layer above the height, reached by the seam's safe travel.
#include <optional>
#include <string>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/print_area.hpp"
#include "gcode/transform/layer_index.hpp"
#include "gcode/transform/splice.hpp"

namespace gcode {

// The tolerance of the join rules (mm): a layer within this of where it
// should sit fits.
inline constexpr double kJoinTolerance = 0.01;

struct JoinStep {
  int layer = 0;        // the new file's layer
  Fixed z_shift;        // where it is printed: its Z plus this
  double scale = 1;     // its extrusion factor
};

struct Join {
  std::vector<int> covered;      // new layers left out: already covered
  std::vector<JoinStep> fills;   // printed first at intermediate heights
  int first = 0;                 // the new layer printed from, then the rest
  double first_scale = 1;        // below 1 only when the new file's last layer overlaps
};

// Where a new file continues a print that reached `printed_z`. Reads the
// index as far as needed. Throws std::runtime_error when the new file has no
// layer above.
Join choose_join(LayerIndex& next, double printed_z, int z_decimals, double tolerance = kJoinTolerance);

// The blocks that continue a print that reached `printed_z` (the top of
// what is printed, with `printed_extent` its XY extent) with `next`, by the
// join rules: the fills under the first new layer, then the new file from it
// to its end. `onto` names the printed side in the seams' comments ("the
// input's layer 12 (Z 2.4)"), `note_prefix` starts them. Throws
// std::runtime_error when `next` has no layer above or lies elsewhere on the
// bed; warns through `diag` (may be null) of a seam that may show.
struct JoinBlocks {
  Join join;
  std::vector<SpliceBlock> blocks;
  std::vector<std::string> report;   // what is printed from `next`, for the user
};
JoinBlocks join_blocks(LayerIndex& next, double printed_z, int z_decimals, const Box2& printed_extent,
                       const std::string& onto, const std::string& note_prefix, Diagnostics* diag);

// The last layer at or below `z` and the first one above it (0 when there
// is none), reading the index as far as needed.
struct Candidates {
  int below = 0;
  int above = 0;
};
Candidates layer_candidates(LayerIndex& index, double z, double tolerance = kJoinTolerance);

// --at-z / --at-layer: the old file is the main stream, the new one indexed.
class RelayerPlan : public SplicePlan {
 public:
  struct Options {
    std::optional<double> at_z;
    int at_layer = 0;
    int z_decimals = 3;
    std::string note_prefix;
  };
  RelayerPlan(LayerIndex& next, Options options, Diagnostics* diag);

  LayerAction at_layer(const LayerInfo& info, const SpliceContext& context) override;
  LayerAction at_end_code(const SpliceContext& context) override;

  bool joined() const { return joined_; }
  // Which layers were joined, for the user.
  const std::vector<std::string>& report() const { return report_; }

 private:
  LayerAction join(const SpliceContext& context);

  LayerIndex& next_;
  Options options_;
  Diagnostics* diag_;
  LayerInfo last_;        // the old file's last kept layer
  int layers_seen_ = 0;
  bool joined_ = false;
  std::vector<std::string> report_;
};

// --resume-from-z: the file is the main stream; its start code and the
// layers at or below the height are left out.
class ResumePlan : public SplicePlan {
 public:
  struct Options {
    double z = 0;               // the measured height of the part
    double lift = 2;            // mm the nozzle is lifted off the part before Z is declared
    double z_speed = 10;        // mm/s
    double purge = 0;           // mm of filament pushed away from the part; 0: none
    double purge_speed = 3;     // mm/s
    double travel_speed = 50;   // mm/s
    bool purge_at_given = false;
    double purge_x = 0, purge_y = 0;
    PrintArea area;             // the bed and the print's box, as far as the file says
    int z_decimals = 3;
    int e_decimals = 5;
    std::string note_prefix;
  };
  ResumePlan(Options options, Diagnostics* diag);

  bool keeps_start_code() const override { return false; }
  LayerAction at_layer(const LayerInfo& info, const SpliceContext& context) override;
  LayerAction at_end_code(const SpliceContext& context) override;

  bool resumed() const { return resumed_; }
  const LayerInfo& first_layer() const { return first_; }
  const std::vector<std::string>& report() const { return report_; }

 private:
  std::vector<std::string> lead_in(const LayerInfo& info, const StreamPoint& main) const;

  Options options_;
  Diagnostics* diag_;
  bool resumed_ = false;
  LayerInfo first_;
  LayerInfo last_skipped_;
  std::vector<std::string> report_;
};

}  // namespace gcode
