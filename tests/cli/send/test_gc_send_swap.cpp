// gc-send's `swap FILE` on the in-process virtual printer: the print goes on
// with a re-sliced file by gc-relayer's rules. What the printer executed is
// held against what gc-relayer writes for the same join (after the same
// layer), whose own tests check it against the sources
// (tests/cli/test_gc_relayer.cpp):
//  * swapped while printing, at the next layer's start: the executed commands
//    are gc-relayer --at-layer L's, one for one (Cura 0.2 -> 0.1 mm layers;
//    PrusaSlicer's relative E with another filament: 220 °C, M900 K0.06);
//  * swapped while paused at a layer's end (0.1 -> 0.2 mm layers: layers
//    already covered, a missing height filled): gc-relayer's, with the pause
//    and resume blocks at the pause, the resume returning exactly there, and
//    the same join reported;
//  * files that cannot join (missing, no layer above, elsewhere on the bed):
//    refused with a message each, and the print goes on unchanged.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "control_run.hpp"
#include "serial_check.hpp"
#include "test_support.hpp"

using gctest::quote;
using gctest::tool_path;

namespace {

std::string pair_path(const std::string& name) { return gctest::fixture_path("pairs/" + name); }

// The commands gc-relayer writes when `next` continues `old` after its layer
// `layer`, and what it reports on stderr.
struct Relayed {
  std::vector<gctest::SentCommand> commands;
  std::string report;
};

Relayed relayed(const std::string& old, const std::string& next, int layer) {
  auto r = gctest::run(quote(tool_path("gc-relayer")) + " --at-layer " + std::to_string(layer) + " " + quote(next) +
                       " < " + quote(old));
  INFO(r.err);
  REQUIRE(r.status == 0);
  return {gctest::commands_of(r.out), r.err};
}

constexpr const char* kFast = "time-scale=2,instant-moves,heat-rate=1000";

int joined_layer(const std::string& err) {
  double layer = gctest::number_after(err, ": joined onto layer ");
  REQUIRE(layer >= 1);
  return static_cast<int>(layer);
}

void require_same(const std::vector<gctest::Executed>& log, const std::vector<gctest::SentCommand>& expected) {
  REQUIRE(log.size() == expected.size() + 1);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    INFO("command " << i << " (expected from line " << expected[i].source_line << ")");
    REQUIRE(log[i].command == expected[i].text);
  }
  CHECK(log.back().command == "M400");
  for (std::size_t i = 1; i < log.size(); ++i) REQUIRE(log[i].number > log[i - 1].number);
}

}  // namespace

TEST_CASE("gc-send swap while printing: from the next layer on, exactly gc-relayer's join", "[gc-send][swap]") {
  struct Pair {
    const char* old;
    const char* next;
  };
  for (Pair p : {Pair{"cura_block_0.2_infill20.gcode", "cura_block_0.1_infill20.gcode"},
                 Pair{"prusa_block_0.2_infill20.gcode", "prusa_block_0.2_infill60_220c_k006.gcode"}}) {
    INFO(p.old << " -> " << p.next);
    const std::string old = pair_path(p.old), next = pair_path(p.next);
    gctest::PauseRun r =
        gctest::send_with_control(old, kFast, "--no-pace", "at_layer 4; echo \"swap " + next + "\" > \"$F\"");
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    CHECK(r.result.err.find("joins at the next layer's start") != std::string::npos);
    const int layer = joined_layer(r.result.err);
    CHECK(layer >= 4);
    CHECK(layer < 20);
    Relayed expected = relayed(old, next, layer);
    require_same(r.log, expected.commands);
    CHECK(r.result.err.find("swaps 1") != std::string::npos);
  }
}

TEST_CASE("gc-send swap while paused: the resume returns, then gc-relayer's join with its covered and filled layers",
          "[gc-send][swap]") {
  const std::string old = pair_path("cura_block_0.1_infill20.gcode"), next = pair_path("cura_block_0.2_infill20.gcode");
  for (const char* when : {"6", "9"}) {
    INFO("paused after layer " << when);
    gctest::PauseRun r = gctest::send_with_control(
        old, kFast, "--no-pace",
        std::string("at_layer ") + when + "; echo pause > \"$F\"; paused; echo \"swap " + next +
            "\" > \"$F\"; sleep 0.1; echo resume > \"$F\"");
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    CHECK(r.result.err.find("joins where the print paused, at the resume") != std::string::npos);
    const int layer = joined_layer(r.result.err);
    Relayed expected = relayed(old, next, layer);
    // gc-relayer's output keeps the old file's lines as they are: its line
    // numbers up to the join are the old file's.
    auto last = static_cast<std::uint64_t>(gctest::number_after(r.result.err, "pause block sent after input line "));
    gctest::Checked c = gctest::check_one_pause(r.log, expected.commands, last);
    // The last command before the blocks is the joined layer's.
    CHECK(c.prefix > 0);
    gcode::MachineState before = gctest::state_after(r.log, c.prefix);
    gcode::MachineState after = gctest::state_after(r.log, c.prefix + c.block);
    for (int a : {gcode::kX, gcode::kY, gcode::kZ, gcode::kE}) CHECK(after.at(a) == before.at(a));
    CHECK(after.relative_e == before.relative_e);
    CHECK(after.feedrate == before.feedrate);
    // The same join, as both tools tell it.
    std::size_t reported = 0;
    for (std::size_t from = 0; from < expected.report.size();) {
      std::size_t nl = expected.report.find('\n', from);
      std::string line = expected.report.substr(from, nl - from);
      from = nl == std::string::npos ? expected.report.size() : nl + 1;
      const std::string tag = "gc-relayer: ";
      if (line.rfind(tag, 0) != 0 || line.find("are kept") != std::string::npos) continue;
      INFO(line);
      CHECK(r.result.err.find("gc-send: swap: " + line.substr(tag.size())) != std::string::npos);
      ++reported;
    }
    CHECK(reported >= 1);
  }
}

TEST_CASE("gc-send swap: a file that cannot join is refused and the print goes on unchanged", "[gc-send][swap]") {
  const std::string old = pair_path("cura_block_0.2_infill20.gcode");
  const std::string missing = gctest::temp_dir() + "/no-such.gcode";
  // The tab is 0.6 mm high: nothing above layer 3; the PrusaSlicer block
  // lies elsewhere on another bed.
  gctest::PauseRun r = gctest::send_with_control(
      old, kFast, "--no-pace",
      "at_layer 4; echo \"swap " + missing + "\" > \"$F\"; echo \"swap " + pair_path("cura_tab_0.2.gcode") +
          "\" > \"$F\"; echo \"swap " + pair_path("prusa_block_0.2_infill20.gcode") + "\" > \"$F\"");
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  CHECK(r.result.err.find("swap " + missing + ": cannot open") != std::string::npos);
  CHECK(r.result.err.find("has no layer above Z") != std::string::npos);
  CHECK(r.result.err.find("prusa_block_0.2_infill20.gcode: ") != std::string::npos);
  CHECK(r.result.err.find("joined onto layer") == std::string::npos);
  require_same(r.log, gctest::commands_of(gctest::read_file(old)));
}

TEST_CASE("gc-send swap twice: the swapped-in file is swapped again, as two gc-relayer joins in a row",
          "[gc-send][swap]") {
  const std::string old = pair_path("cura_block_0.2_infill20.gcode");
  const std::string thin = pair_path("cura_block_0.1_infill20.gcode"), dense = pair_path("cura_block_0.2_infill60.gcode");
  gctest::PauseRun r = gctest::send_with_control(old, kFast, "--no-pace",
                                                 "at_layer 4; echo \"swap " + thin + "\" > \"$F\"; at_layer 14; echo \"swap " +
                                                     dense + "\" > \"$F\"");
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  const std::string& err = r.result.err;
  const int first = joined_layer(err);
  const std::size_t second_at = err.find(": joined onto layer ", err.find(": joined onto layer ") + 1);
  REQUIRE(second_at != std::string::npos);
  const int second = joined_layer(err.substr(second_at));
  CHECK(second > first);
  auto once = gctest::run(quote(tool_path("gc-relayer")) + " --at-layer " + std::to_string(first) + " " + quote(thin) +
                          " < " + quote(old) + " | " + quote(tool_path("gc-relayer")) + " --at-layer " +
                          std::to_string(second) + " " + quote(dense));
  REQUIRE(once.status == 0);
  require_same(r.log, gctest::commands_of(once.out));
  CHECK(err.find("swaps 2") != std::string::npos);
}
