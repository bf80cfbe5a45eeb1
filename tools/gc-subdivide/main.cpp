// gc-subdivide: cut long moves into short pieces so the printer's buffer holds
// only a few millimetres (or milliseconds) of motion, for a fast pause.
#include <fmt/format.h>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/subdivide_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/subdivide.hpp"

namespace {

// The input with its long moves cut, and what was cut (-v).
int subdivide(gcode::cli::SubdivideToolOptions& o, gcode::Diagnostics& diag) {
  gcode::LayerSelection where;
  // Without a selection the layer tracker holds nothing back.
  const bool selected = o.selected();
  gcode::cli::Filter run(o.io, gcode::PipelineOptions{.layers = selected});
  if (selected) where = run.selection(o.where);
  gcode::Subdivider subdivider(o.split, run.pipeline().precision(), &diag, selected ? &where : nullptr);
  run.add(subdivider);
  run.write([&] { run.check_selection(where, diag, "split"); });
  const gcode::SubdivideStats& s = subdivider.stats();
  diag.info(fmt::format("{} lines in, {} moves cut into {} pieces ({} arcs), {} bytes out", s.lines, s.moves_split,
                        s.pieces, s.arcs, run.output()->bytes_written()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return gcode::cli::run_filter(
      argc, argv, "gc-subdivide",
      "gc-subdivide: cut long moves into short pieces so the printer's buffer holds only a few mm (or ms) of\n"
      "motion and reacts quickly to a pause. Put it just before gc-send:\n"
      "  gc-subdivide --max 0.2 part.gcode | gc-send --port /dev/ttyACM0\n"
      "A move longer than the limit becomes equal pieces; absolute E ends on the input's own value,\n"
      "relative E and G91 pieces sum exactly to the written amount; F and the comment stay on the first\n"
      "piece. Pure Z and E moves, G10/G11 and short moves are left alone; other lines pass byte for byte.",
      gcode::cli::add_subdivide_options, subdivide);
}
