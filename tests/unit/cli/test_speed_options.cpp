// gc-speedup's options (cli/speed_options.hpp): one change is required, the
// restore goes with --m220; from the input: the filament for --max-flow (the
// file's, else 1.75 with a warning), the M220 restore for auto (Marlin 2:
// B/R), a ramp's layers; the messages after a change.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/cli/speed_options.hpp"
#include "capture.hpp"
#include "tool_run.hpp"
#include "test_support.hpp"

using gcode::cli::SpeedToolOptions;

namespace {

int parse(std::vector<std::string> args, SpeedToolOptions& o, std::string* err = nullptr) {
  gcode::cli::Tool tool("gc-test", "A test tool");
  gcode::cli::add_speed_options(tool, o);
  return gctest::parse_options(tool, std::move(args), err);
}

std::string print(const std::string& header) {
  std::string s = header + "M82\nG28\n";
  for (int i = 0; i < 3; ++i)
    s += ";LAYER:" + std::to_string(i) + "\nG1 Z" + std::to_string(i + 1) + " F600\nG1 X10 E" + std::to_string(i + 1) +
         "\nG1 X0 E" + std::to_string(i + 1) + ".5\n";
  return s;
}

// Parses `args` with FILE holding `text`, then resolves from it; returns the warnings.
std::string resolve(std::vector<std::string> args, const std::string& text, SpeedToolOptions& o) {
  const std::string path = gctest::temp_dir() + "/in.gcode";
  gctest::write_file(path, text);
  args.push_back(path);
  REQUIRE(parse(args, o) == 0);
  return gctest::stderr_of([&] {
    gcode::Diagnostics diag("gc-test");
    gcode::cli::Filter run(o.io);
    gcode::LayerSelection where = run.selection(o.where);
    gcode::cli::resolve_speed_from_input(o, run, where, diag);
  });
}

}  // namespace

TEST_CASE("speed options: one change, the restore only with --m220", "[speed_options]") {
  SpeedToolOptions o;
  std::string err;
  CHECK(parse({}, o, &err) == 2);
  CHECK(err == "gc-test: give the change: --factor F, --speed MM_S or --ramp F1:F2 (see gc-test --help)\n");
  SpeedToolOptions r;
  CHECK(parse({"--factor", "2", "--m220-restore", "reset"}, r, &err) == 2);
  CHECK(err == "gc-test: --m220-restore goes with --m220 (see gc-test --help)\n");
  SpeedToolOptions bad;
  CHECK(parse({"--ramp", "1-2"}, bad, &err) == 2);
  CHECK(err == "gc-test: --ramp: '1-2' is not F1:F2 (e.g. 1:3) (see gc-test --help)\n");
  SpeedToolOptions ramp;
  REQUIRE(parse({"--ramp", "1:0.5", "--filament-diameter", "2.85"}, ramp) == 0);
  CHECK(ramp.speed.ramp);
  CHECK(ramp.speed.ramp_first == 1);
  CHECK(ramp.speed.ramp_last == 0.5);
  CHECK(ramp.diameter_given);
}

TEST_CASE("speed options: the filament, the M220 restore and the ramp's layers from the input", "[speed_options]") {
  SpeedToolOptions flow;
  CHECK(resolve({"--factor", "2", "--max-flow", "10"}, print("; filament_diameter = 2.85\n"), flow).empty());
  CHECK(flow.speed.filament_diameter == 2.85);
  SpeedToolOptions guessed;
  const std::string warned = resolve({"--factor", "2", "--max-flow", "10"}, print(""), guessed);
  CHECK(warned.starts_with("gc-test: warning: "));
  CHECK(warned.ends_with("/in.gcode names no filament diameter; --max-flow assumes 1.75 mm (give --filament-diameter)\n"));
  CHECK(guessed.speed.filament_diameter == 1.75);
  SpeedToolOptions marlin2;
  resolve({"--factor", "2", "--m220"}, print("; gcode_flavor = marlin2\n"), marlin2);
  CHECK(marlin2.speed.m220_restore == gcode::M220Restore::Backup);
  SpeedToolOptions other;
  resolve({"--factor", "2", "--m220"}, print("; gcode_flavor = klipper\n"), other);
  CHECK(other.speed.m220_restore == gcode::M220Restore::Reset);
  SpeedToolOptions percents;
  CHECK(resolve({"--factor", "1.333", "--m220", "--m220-restore", "backup"}, print(""), percents) ==
        "gc-test: warning: --m220: the firmware takes whole percents; x1.333 is written M220 S133\n");
  CHECK(percents.speed.m220_restore == gcode::M220Restore::Backup);
  SpeedToolOptions ramp;
  resolve({"--ramp", "1:2", "--layers", "2-"}, print(""), ramp);
  CHECK(ramp.speed.ramp_layers == std::vector<int>{2, 3});
}

TEST_CASE("speed options: the messages after a change", "[speed_options]") {
  gcode::SpeedOptions s;
  s.max_flow = 12;
  s.max_speed = 150;
  gcode::SpeedStats stats;
  stats.capped_flow = 3;
  stats.capped_max_speed = 2;
  stats.left_alone = 1;
  stats.moves_changed = 40;
  stats.lines_edited = 12;
  stats.restores = 2;
  stats.layers = {4, 5};
  const std::string said = gctest::stderr_of([&] {
    gcode::Diagnostics diag("gc-test", 1);
    gcode::cli::report_speed_change(s, stats, diag);
  });
  CHECK(said ==
        "gc-test: warning: 5 moves capped: 3 by --max-flow 12 mm3/s (filament 1.75 mm), 2 by --max-speed 150 mm/s\n"
        "gc-test: warning: 1 moves of the region left at their speed\n"
        "gc-test: 40 moves in 2 layers at a new speed; 12 lines edited (2 put the original F back)\n");
}
