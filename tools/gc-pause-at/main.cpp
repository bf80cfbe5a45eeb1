// gc-pause-at: insert a clean pause (retract, park, wait, resume exactly) at
// layer boundaries. The rules are the library's: pause_stage.hpp (where),
// pause_context.hpp (park), pause_sequence.hpp (the blocks).
#include <algorithm>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/pause_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/pause_stage.hpp"

namespace {

using gcode::cli::UsageError;

struct Options {
  gcode::cli::FilterOptions io;
  std::string before_layer, after_layer, heights;
  int every = 0;
  bool dry_run = false;
  gcode::cli::PauseOptions pause;
  gcode::PauseTriggers where;
};

std::vector<double> numbers(const std::string& text, const char* option) {
  std::vector<double> list;
  if (!gcode::parse_number_list(text, list)) throw UsageError(std::string(option) + ": '" + text + "' is not a list of numbers");
  return list;
}

// What the options say, checked before anything is read.
void resolve(Options& o) {
  if (!o.before_layer.empty()) o.where.before = gcode::LayerRange::parse(o.before_layer);
  if (!o.after_layer.empty()) o.where.after = gcode::LayerRange::parse(o.after_layer);
  if ((o.where.before && o.where.before->needs_total()) || (o.where.after && o.where.after->needs_total()))
    throw UsageError("layers counted from the end ('-N') are not known while streaming; name them");
  if (!o.heights.empty()) {
    o.where.heights = numbers(o.heights, "--z");
    std::sort(o.where.heights.begin(), o.where.heights.end());
  }
  o.where.every = o.every;
  if (!o.where.any()) throw UsageError("nothing to do: give --before-layer, --after-layer, --z or --every");
  gcode::cli::resolve_pause_options(o.pause);
}

int run(Options& o, gcode::Diagnostics& diag) {
  gcode::PauseConfig& c = o.pause.config;
  gcode::cli::load_pause_texts(o.pause);
  gcode::cli::Filter run(o.io);
  gcode::ParkRules park = gcode::cli::park_rules(o.pause, run.print_area(), c);
  o.where.check_heights(park.area);
  gcode::PauseStage pauses(o.where, park, c, run.pipeline().precision(), diag, "gc-pause-at: ");
  run.add(pauses);
  auto verify = [&] { o.where.verify(pauses.layers(), pauses.top_layer_z()); };
  if (!o.dry_run) {
    run.write(verify);
    return 0;
  }
  pauses.set_dry_run(true);
  run.run();
  verify();
  gcode::OutputFile file(o.io.output, std::string());
  gcode::OutputBuffer out(file.fd());
  out.write(gcode::pause_table(pauses.pauses()));
  out.flush();
  file.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  o.pause.config.message = "Paused at layer {layer}";
  gcode::cli::Tool tool("gc-pause-at",
                        "Insert a clean pause at layer boundaries: retract, lift, park at the back of the bed, wait,\n"
                        "then heat, return to exactly where printing stopped and restore every mode.\n"
                        "The pause goes after the last move of the previous layer and before the move to the\n"
                        "next layer's Z. Several pauses may be given in one run.");
  CLI::App& app = tool.app();
  const auto& positive = gcode::cli::positive();
  tool.add_filter_options(o.io, gcode::cli::kFilter & ~gcode::cli::kLayerMarker);

  const char* where = "Where (at least one; they combine)";
  app.add_option("--before-layer", o.before_layer, "Pause before these layers print (1 = first printed layer): 5, 5-9, 5,7,9-12")
      ->type_name("RANGE")->group(where);
  app.add_option("--after-layer", o.after_layer, "Pause once these layers are printed (N = before layer N+1)")
      ->type_name("RANGE")->group(where);
  app.add_option("--z", o.heights, "Pause before the first layer whose Z is above each height (mm, comma list)")
      ->type_name("HEIGHTS")->group(where);
  app.add_option("--every", o.every, "Pause every N layers (before layers N+1, 2N+1, ...)")
      ->type_name("N")->check(positive)->group(where);
  app.add_option("--layer-marker", o.io.layer_marker, "RE2 pattern of the layer comment, for files from other slicers")
      ->type_name("REGEX")->check(gcode::cli::layer_marker_pattern())->group(where);
  app.add_flag("--dry-run", o.dry_run, "List where each pause goes (layer, Z, line, park) and write no G-code")
      ->group(where)->excludes(app.get_option("-i"));

  gcode::cli::add_pause_options(tool, o.pause, true);
  tool.check([&] { resolve(o); });

  return tool.run(argc, argv, [&] {
    gcode::Diagnostics diag = tool.diagnostics(o.io);
    return run(o, diag);
  });
}
