#pragma once
// gc-relayer's options and what they map to: the join of a re-sliced file
// (--at-z, --at-layer: relayer.hpp's RelayerPlan), the resume of a failed
// print (--resume-from-z: ResumePlan) and the list of the layers nearest a
// measured height (--list-candidates).
#include <optional>
#include <string>

#include "gcode/cli/tool.hpp"
#include "gcode/transform/relayer.hpp"
#include "gcode/transform/seam.hpp"

namespace gcode::cli {

struct RelayerToolOptions {
  FilterOptions io;
  SeamOptions seam;
  std::optional<double> at_z;
  int at_layer = 0;
  std::optional<double> resume_z;
  std::optional<double> candidates_z;
  double resume_lift = 2;
  double purge = 0;
  double purge_speed = 3;
  std::string purge_at;
};

// FILE, -o, -q, -v, --layer-marker, --e-mode, the four modes (exactly one
// is a usage error otherwise), the resume's options and the seam's.
void add_relayer_options(Tool& tool, RelayerToolOptions& options);

// The plan options of each mode (notes prefixed "gc-relayer: ").
RelayerPlan::Options join_plan_options(const RelayerToolOptions& options);
// Without the print area, which comes from the input. Throws UsageError for
// a --purge-at that is not X,Y.
ResumePlan::Options resume_plan_options(const RelayerToolOptions& options);

// --list-candidates: the layers of FILE just below and just above the
// height, one line each, as printed. Throws InputError when FILE has no layers.
std::string layer_candidates_text(const RelayerToolOptions& options);

}  // namespace gcode::cli
