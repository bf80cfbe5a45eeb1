// gc-pause-at: insert a clean pause (retract, park, wait, resume exactly) at
// layer boundaries. The rules are the library's: pause_stage.hpp (where),
// pause_context.hpp (park), pause_sequence.hpp (the blocks).
#include "gcode/cli/filter.hpp"
#include "gcode/cli/pause_at_options.hpp"
#include "gcode/cli/pause_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/pause_stage.hpp"

namespace {

using Options = gcode::cli::PauseAtOptions;

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
  gcode::cli::add_pause_at_options(tool, o);

  return tool.run(argc, argv, [&] {
    gcode::Diagnostics diag = tool.diagnostics(o.io);
    return run(o, diag);
  });
}
