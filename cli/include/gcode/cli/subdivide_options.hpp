#pragma once
// gc-subdivide's options and what they map to (transform/subdivide.hpp's
// SubdivideOptions): the limit (--max or --latency with --buffer), the rate
// cap (--max-rate or --baud), the floor (--min), travel and arcs, and the
// region (--layers, --z-range, --types).
#include <string>

#include "gcode/cli/tool.hpp"
#include "gcode/pipeline/selection.hpp"
#include "gcode/transform/subdivide.hpp"

namespace gcode::cli {

struct SubdivideToolOptions {
  FilterOptions io;
  SubdivideOptions split;
  SelectionText where;
  double baud = 0;
  std::string arcs = "split";

  // A region was asked for: layer numbers need the layer tracker.
  bool selected() const { return !where.layers.empty() || !where.z_range.empty() || !where.types.empty(); }
};

// Every option, and the check that settles the rate, the floor and the
// limit (a usage error: no limit and no --arcs split, SubdivideOptions::validate).
void add_subdivide_options(Tool& tool, SubdivideToolOptions& options);

}  // namespace gcode::cli
