// gc-swap-layer: replace, skip, repeat layers and insert blocks between them,
// with seams the printer cannot tell (the splice of lib/transform/splice.hpp).
#include <fmt/format.h>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/seam_options.hpp"
#include "gcode/cli/swap_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/layer_edits.hpp"
#include "gcode/transform/splice.hpp"

namespace {

// The input with its layer edits spliced in, and what was done (-v).
int swap(gcode::cli::SwapToolOptions& o, gcode::Diagnostics& diag) {
  gcode::cli::Filter run(o.io);
  gcode::cli::SpliceFiles others;  // --with and --file
  std::vector<gcode::SpliceFile> files = others.open(o.edits.files(), run.markers());
  int total = o.edits.needs_total() ? run.count_layers() : 0;
  int main_fd = -1;
  if (!o.edits.repeat.empty()) {
    // --repeat reads a layer of the input again: a pipe is kept in a temp file.
    run.input().make_seekable();
    main_fd = run.input().fd();
  }
  gcode::cli::splice_printer(run, files, o.seam, diag);
  gcode::LayerEditPlan plan(o.edits, main_fd, run.markers(), files, total, run.pipeline().precision().of('Z'), &diag,
                            "gc-swap-layer: ");
  gcode::SpliceStage splice(plan, run.pipeline().precision(), o.seam, &diag);
  run.add(splice);
  run.write([&] { plan.verify(); });
  for (const std::string& line : plan.report()) diag.info(line);
  diag.info(fmt::format("{} layers kept, {} left out, {} blocks printed, {} layers written", splice.layers_kept(),
                        splice.layers_left_out(), splice.blocks(), splice.layers_out()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return gcode::cli::run_filter(
      argc, argv, "gc-swap-layer",
      "gc-swap-layer: replace, skip and repeat layers of a print, or insert a block after a layer, with seams the\n"
      "printer cannot tell: E carried (G92 E), modes, feed rate, tool, temperatures, fan, flow and pressure advance\n"
      "restored, every travel across a seam lifted above everything printed so far. Edits apply in layer order:\n"
      "  gc-swap-layer --layer 30-40 --with dense.gcode part.gcode > out.gcode\n"
      "  gc-swap-layer --skip 12-14 --repeat 20x2 part.gcode > out.gcode\n"
      "Layers count from 1 as gc-layers counts them; @Z names a layer by its height (@1.2, @1:2.4).\n"
      "Kept lines pass byte for byte, or with their Z shifted where layers were left out or added.",
      gcode::cli::add_swap_options, swap);
}
