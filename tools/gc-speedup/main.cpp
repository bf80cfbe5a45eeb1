// gc-speedup: change print speed by layer, height or feature, exactly: every
// move that inherits F is changed too, and the original F is back on the
// first move after the region. The rules are the library's (transform/speed.hpp),
// the options cli/speed_options.hpp's.
#include <optional>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/speed_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/report/layer_time.hpp"
#include "gcode/transform/speed.hpp"

namespace {

int run(gcode::cli::SpeedToolOptions& o, gcode::cli::Tool& tool) {
  gcode::Diagnostics diag = tool.diagnostics(o.io);
  gcode::cli::Filter run(o.io);
  gcode::LayerSelection where = run.selection(o.where);
  gcode::cli::resolve_speed_from_input(o, run, where, diag);
  gcode::SpeedStage stage(o.speed, run.pipeline().precision(), &diag, &where);
  // -v: the estimate before and after, per layer of the region and in total.
  std::optional<gcode::LayerTimer> before, after;
  if (o.io.verbosity() >= 1) {
    before.emplace();
    run.add(*before);
  }
  run.add(stage);
  if (o.io.verbosity() >= 1) {
    after.emplace();
    run.add(*after);
  }
  run.write([&] { run.check_selection(where, diag, "changed"); });
  gcode::cli::report_speed_change(o.speed, stage.stats(), diag);
  if (before && after)
    for (const std::string& line : gcode::time_change_lines(before->times(), after->times(), stage.stats().layers))
      diag.info(line);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  gcode::cli::SpeedToolOptions o;
  gcode::cli::Tool tool(
      "gc-speedup",
      "gc-speedup: change print speed by layer, height or feature, exactly. F is modal: every move of the\n"
      "region runs at its original speed times the factor, also moves that inherit F, and the first move\n"
      "after the region gets its original F back. Positions, E and every other line stay byte for byte;\n"
      "an edited line gets a '; gc-speedup x3' comment, and a region already changed is refused.\n"
      "  gc-speedup --factor 0.5 --layers 1-3 part.gcode | gc-send --port /dev/ttyACM0\n"
      "  gc-speedup --factor 1.5 --types FILL --max-flow 12 -i part.gcode");
  gcode::cli::add_speed_options(tool, o);
  return tool.run(argc, argv, [&] { return run(o, tool); });
}
