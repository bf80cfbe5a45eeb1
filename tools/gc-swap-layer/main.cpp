// gc-swap-layer: replace, skip, repeat layers and insert blocks between them,
// with seams the printer cannot tell (the splice of lib/transform/splice.hpp).
#include <fmt/format.h>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/seam_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/layer_edits.hpp"
#include "gcode/transform/splice.hpp"

namespace {

struct Options {
  gcode::cli::FilterOptions io;
  gcode::LayerEditsText edits;
  gcode::SeamOptions seam;
};

}  // namespace

int main(int argc, char** argv) {
  Options o;
  gcode::cli::Tool tool(
      "gc-swap-layer",
      "gc-swap-layer: replace, skip and repeat layers of a print, or insert a block after a layer, with seams the\n"
      "printer cannot tell: E carried (G92 E), modes, feed rate, tool, temperatures, fan, flow and pressure advance\n"
      "restored, every travel across a seam lifted above everything printed so far. Edits apply in layer order:\n"
      "  gc-swap-layer --layer 30-40 --with dense.gcode part.gcode > out.gcode\n"
      "  gc-swap-layer --skip 12-14 --repeat 20x2 part.gcode > out.gcode\n"
      "Layers count from 1 as gc-layers counts them; @Z names a layer by its height (@1.2, @1:2.4).\n"
      "Kept lines pass byte for byte, or with their Z shifted where layers were left out or added.");
  CLI::App& app = tool.app();
  tool.add_filter_options(o.io);
  app.add_option("--layer", o.edits.replace, "Replace these layers (RANGE or @Z1:Z2; repeatable, each with a --with)")
      ->allow_extra_args(false)
      ->type_name("RANGE");
  app.add_option("--with", o.edits.with,
                 "...by the layers of FILE at the same Z, or by FILE's LAYERS in order; placed at the replaced Z")
      ->allow_extra_args(false)
      ->type_name("FILE[:LAYERS]");
  app.add_option("--skip", o.edits.skip, "Leave these layers out; later layers come down by their thickness")
      ->type_name("RANGE");
  app.add_flag("--keep-z", o.edits.keep_z,
               "With --skip: keep every Z and scale the next layer's extrusion by (h + skipped) / h (over-extrudes "
               "by design)");
  app.add_option("--repeat", o.edits.repeat, "Print LAYER N more times (default 1), later layers up (repeatable)")
      ->allow_extra_args(false)
      ->type_name("LAYER[xN]");
  app.add_option("--insert-after", o.edits.insert_after,
                 "Print the layers of the --file after LAYER, on top of it; later layers up (repeatable)")
      ->allow_extra_args(false)
      ->type_name("LAYER");
  app.add_option("--file", o.edits.insert_file, "The block for an --insert-after (its layers; start and end code left out)")
      ->allow_extra_args(false)
      ->type_name("FILE");
  gcode::cli::add_seam_options(tool, o.seam);
  tool.check([&] {
    o.edits.validate();
    o.seam.validate();
  });

  return tool.run(argc, argv, [&] {
    gcode::Diagnostics diag = tool.diagnostics(o.io);
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
  });
}
