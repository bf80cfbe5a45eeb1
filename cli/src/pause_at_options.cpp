#include "gcode/cli/pause_at_options.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>


namespace gcode::cli {

namespace {

// What the options say, checked before anything is read.
void resolve(PauseAtOptions& o) {
  if (!o.before_layer.empty()) o.where.before = LayerRange::parse(o.before_layer);
  if (!o.after_layer.empty()) o.where.after = LayerRange::parse(o.after_layer);
  if ((o.where.before && o.where.before->needs_total()) || (o.where.after && o.where.after->needs_total()))
    throw UsageError("layers counted from the end ('-N') are not known while streaming; name them");
  if (!o.heights.empty()) {
    o.where.heights = option_numbers(o.heights, "--z");
    std::sort(o.where.heights.begin(), o.where.heights.end());
  }
  o.where.every = o.every;
  if (!o.where.any()) throw UsageError("nothing to do: give --before-layer, --after-layer, --z or --every");
  resolve_pause_options(o.pause);
}

}  // namespace

void add_pause_at_options(Tool& tool, PauseAtOptions& o) {
  CLI::App& app = tool.app();
  tool.add_filter_options(o.io, kFilter & ~kLayerMarker);
  const char* where = "Where (at least one; they combine)";
  app.add_option("--before-layer", o.before_layer, "Pause before these layers print (1 = first printed layer): 5, 5-9, 5,7,9-12")
      ->type_name("RANGE")->group(where);
  app.add_option("--after-layer", o.after_layer, "Pause once these layers are printed (N = before layer N+1)")
      ->type_name("RANGE")->group(where);
  app.add_option("--z", o.heights, "Pause before the first layer whose Z is above each height (mm, comma list)")
      ->type_name("HEIGHTS")->group(where);
  app.add_option("--every", o.every, "Pause every N layers (before layers N+1, 2N+1, ...)")
      ->type_name("N")->check(positive())->group(where);
  app.add_option("--layer-marker", o.io.layer_marker, "RE2 pattern of the layer comment, for files from other slicers")
      ->type_name("REGEX")->check(layer_marker_pattern())->group(where);
  app.add_flag("--dry-run", o.dry_run, "List where each pause goes (layer, Z, line, park) and write no G-code")
      ->group(where)->excludes(app.get_option("-i"));
  add_pause_options(tool, o.pause, true);
  tool.check([&o] { resolve(o); });
}

}  // namespace gcode::cli
