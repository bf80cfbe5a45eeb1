#include "gcode/cli/swap_options.hpp"

#include <CLI/CLI.hpp>

namespace gcode::cli {

void add_swap_options(Tool& tool, SwapToolOptions& o) {
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
  add_seam_options(tool, o.seam);
  tool.check([&o] {
    o.edits.validate();
    o.seam.validate();
  });
}

}  // namespace gcode::cli
