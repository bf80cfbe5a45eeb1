#include "gcode/cli/layers_options.hpp"

#include <CLI/CLI.hpp>

#include "gcode/core/layer_range.hpp"

namespace gcode::cli {

void add_layers_options(Tool& tool, LayersToolOptions& o) {
  CLI::App& app = tool.app();
  tool.add_filter_options(o.io);
  app.add_flag("--json", o.json, "Print the table as JSON (schema gc-layers/1, see the man page)");
  app.add_option("--extract", o.extract,
                 "Write start code, the layers in RANGE and end code as printable G-code "
                 "(RANGE: 5, 5-9, 5-, -3 for the last three, 5,7,9-12)")
      ->type_name("RANGE");
  app.add_option("--z-range", o.z_range, "Write the layers whose Z lies in Z1:Z2 (either side may be empty)")
      ->type_name("Z1:Z2");
  app.add_option("--where", o.where, "Print first line, last line, first byte and end byte of layer N")
      ->type_name("N")
      ->check(positive());
  app.add_option("--density", o.density, "Filament density in g/cm3 for the mass (default PLA 1.24)")
      ->check(positive());
  app.add_option("--filament-diameter", o.filament_diameter, "Filament diameter in mm (default: the slicer's, else 1.75)")
      ->check(positive());
  app.add_flag("--time", o.time,
               "Add the estimated print time per layer and cumulative (h:mm:ss), and the total; "
               "limits from the file's M201/M203/M204/M205, else --profile, else PrusaSlicer's config block, else Marlin's defaults");
  app.add_option("--profile", o.profile,
                 "Machine limits: a key = value file (a PrusaSlicer config.ini works), or the built-in cura or marlin")
      ->type_name("FILE");
  app.add_flag("--time-by-feature", o.time_by_feature,
               "With --time: also the layers' time by ;TYPE: feature, travel, layer changes, retraction, at nominal "
               "speed, and what acceleration costs apart");
  app.add_flag("--no-heat-time", o.no_heat_time, "Leave heating waits (M109, M190) out of the time, as slicers do");
  app.add_option("--svg", o.svg, "Draw layer(s) RANGE from above as SVG (to --svg-out, or standard output)")->type_name("RANGE");
  app.add_option("--svg-sheet", o.svg_sheet, "Draw the layers in RANGE on one SVG page, as a grid")->type_name("RANGE");
  app.add_option("--svg-out", o.svg_out, "Where the SVG goes; with several layers a pattern such as layer-{}.svg")
      ->type_name("PATH");
  app.add_flag("--no-travel", o.no_travel, "Leave travel moves out of the pictures");
  app.add_option("--svg-size", o.svg_size, "Size of a layer's picture in pixels (default 800)")
      ->type_name("PX")
      ->check(CLI::Range(50.0, 20000.0));
  tool.check([&o] {
    if (o.time_by_feature) o.time = true;
    if (o.io.in_place && !o.cutting()) throw UsageError("--in-place goes with --extract or --z-range");
    if (!o.io.output.empty() && !o.cutting()) throw UsageError("-o goes with --extract or --z-range");
    if (o.cutting() && (o.json || o.where > 0)) throw UsageError("cutting does not combine with --json or --where");
    if (!o.svg.empty() && !o.svg_sheet.empty()) throw UsageError("--svg and --svg-sheet exclude each other");
    if (o.pictures() && (o.cutting() || o.json || o.where > 0))
      throw UsageError("pictures do not combine with --extract, --z-range, --json or --where");
    if (!o.svg_out.empty() && !o.pictures()) throw UsageError("--svg-out goes with --svg or --svg-sheet");
    for (const std::string* r : {&o.extract, &o.svg, &o.svg_sheet})
      if (!r->empty()) LayerRange::parse(*r);
    if (!o.z_range.empty()) ZRange::parse(o.z_range);
  });
}

}  // namespace gcode::cli
