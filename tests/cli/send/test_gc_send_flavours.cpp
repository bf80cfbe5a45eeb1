// gc-send on each firmware flavour of the built-in virtual printer
// (virtual:firmware=marlin|klipper|prusa|rrf), each with a real fixture
// sliced for such a printer, cut into 0.2 mm pieces by gc-subdivide: the
// flavour is detected from M115, a FIFO pause and resume leave every
// command once and in order in the executed log with the blocks at one
// place, a cancel ends safely, and there is no timeout; then what each
// firmware does its own way: Klipper's "!!" errors and unknown commands
// (the print goes on), Prusa's own pause (M601) and silent M600, and
// gc-virtual-printer --firmware klipper on a pseudo-terminal.
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <vector>

#include "control_run.hpp"
#include "pty_run.hpp"
#include "serial_check.hpp"
#include "test_support.hpp"

using gctest::check_one_pause;
using gctest::number_after;
using gctest::PauseRun;
using gctest::quote;
using gctest::send_with_control;
using gctest::tool_path;

namespace {

struct Flavour {
  const char* name;      // virtual:firmware=
  const char* fixture;   // sliced for such a printer
  const char* detected;  // the flavour gc-send names once M115 is answered
};

const Flavour kFlavours[] = {
    {"marlin", "prusa_dome_varlayer_ender3_abs.gcode", ""},
    {"klipper", "prusa_pegs_0.2_klipper_zhop_labels.gcode", "klipper"},
    {"prusa", "prusa_cube_0.2_mk3s_rel_zhop.gcode", "prusa"},
    {"rrf", "prusa_tshape_0.2_rrf_fwretract.gcode", "reprapfirmware"},
};

// The start code and first three layers of a fixture in 0.2 mm pieces,
// written once per fixture.
const std::string& pieces_of(const std::string& fixture) {
  static std::map<std::string, std::string> paths;
  std::string& path = paths[fixture];
  if (path.empty()) {
    path = gctest::temp_dir() + "/" + fixture + ".pieces";
    auto r = gctest::run(quote(tool_path("gc-subdivide")) + " --max 0.2 " + quote(gctest::fixture_path(fixture)) +
                         " | awk '/^;LAYER_CHANGE/ { if (++n == 4) exit } { print }' > " + quote(path));
    REQUIRE(r.status == 0);
  }
  return path;
}

// Instant moves: the run lasts as long as the link takes.
std::string printer(const Flavour& f) {
  return std::string("firmware=") + f.name + ",time-scale=20,instant-moves,heat-rate=1000";
}

void check_detected(const Flavour& f, const std::string& err) {
  if (*f.detected != 0) CHECK(err.find(std::string("(flavour ") + f.detected + ")") != std::string::npos);
  CHECK(err.find("timeouts 0") != std::string::npos);
  CHECK(err.find("no answer for") == std::string::npos);
}

}  // namespace

TEST_CASE("gc-send flavours: a FIFO pause and resume on each firmware, every command once and in order",
          "[gc-send][flavour]") {
  for (const Flavour& f : kFlavours) {
    INFO("firmware " << f.name << ", " << f.fixture);
    const std::string& file = pieces_of(f.fixture);
    auto input = gctest::commands_of(gctest::read_file(file));
    REQUIRE(input.size() > 2000);
    PauseRun r = send_with_control(file, printer(f), "--no-pace",
                                   "at_layer 1; echo pause > \"$F\"; paused; echo resume > \"$F\"");
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    check_detected(f, r.result.err);
    std::uint64_t last = static_cast<std::uint64_t>(number_after(r.result.err, "pause block sent after input line "));
    gctest::Checked c = check_one_pause(r.log, input, last);
    gcode::MachineState before = gctest::state_after(r.log, c.prefix);
    gcode::MachineState after = gctest::state_after(r.log, c.prefix + c.block);
    for (int a : {gcode::kX, gcode::kY, gcode::kZ, gcode::kE}) CHECK(after.at(a) == before.at(a));
    CHECK(after.relative_e == before.relative_e);
    // Nothing in the blocks that the firmware refuses: a plain Klipper (no
    // display) answers M117 '// Unknown command:"M117"'; the others show it.
    bool message = false;
    for (std::size_t i = c.prefix; i < c.prefix + c.block; ++i) message = message || r.log[i].command.rfind("M117", 0) == 0;
    CHECK(message == (std::string(f.name) != "klipper"));
  }
}

TEST_CASE("gc-send flavours: a cancel on each firmware ends safely after the commands sent, in order",
          "[gc-send][flavour]") {
  for (const Flavour& f : kFlavours) {
    INFO("firmware " << f.name << ", " << f.fixture);
    const std::string& file = pieces_of(f.fixture);
    auto input = gctest::commands_of(gctest::read_file(file));
    PauseRun r = send_with_control(file, printer(f), "--no-pace", "at_layer 1; executed 1500; echo cancel > \"$F\"");
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    check_detected(f, r.result.err);
    CHECK(r.result.err.find("cancelled after input line") != std::string::npos);
    // The progress line ends the print as cancelled, never as done.
    CHECK(r.result.err.find("gc-send: cancelled ") != std::string::npos);
    CHECK(r.result.err.find("gc-send: done ") == std::string::npos);
    std::size_t prefix = 0;
    while (prefix < input.size() && prefix < r.log.size() && r.log[prefix].command == input[prefix].text) ++prefix;
    CHECK(prefix > 100);
    CHECK(prefix < input.size());
    REQUIRE(r.log.size() > prefix + 5);
    std::vector<std::string> tail;
    for (std::size_t i = r.log.size() - 5; i < r.log.size(); ++i) tail.push_back(r.log[i].command);
    CHECK(tail == std::vector<std::string>{"M104 S0", "M140 S0", "M107", "M84", "M400"});
  }
}

TEST_CASE("gc-send on Klipper: '!!' errors and unknown commands are warnings, the print goes on", "[gc-send][flavour]") {
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/early_move.gcode", log = dir + "/executed.log";
  // A move before G28: Klipper refuses it ("!! Must home axis first") and
  // says ok; M201 is Marlin's, not Klipper's.
  gctest::write_file(file, "G1 X5 F3000\nM201 X1000 Y1000\nG28\n" + gctest::read_file(pieces_of(kFlavours[1].fixture)));
  // On the simulated clock: no overdue answer, so no question of gc-send's
  // own, however loaded the machine.
  auto r = gctest::run(quote(tool_path("gc-send")) + " --port virtual:" + printer(kFlavours[1]) +
                       ",simulated-clock,log=" + log + " " + quote(file));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find("printer error: Must home axis first") != std::string::npos);
  CHECK(r.err.find("the printer did not take a command: Unknown command:\"M201\"") != std::string::npos);
  CHECK(r.err.find(", not taken by the firmware ") != std::string::npos);  // counted in the summary
  auto input = gctest::commands_of(gctest::read_file(file));
  auto executed = gctest::read_log(log);
  // Everything ran once, in order, but the refused move.
  REQUIRE(executed.size() == input.size());  // (the final M400 makes up for it)
  for (std::size_t i = 1; i < input.size(); ++i) REQUIRE(executed[i - 1].command == input[i].text);
  CHECK(executed.back().command == "M400");
}

TEST_CASE("gc-send on Klipper: a shutdown mid-print is reported as failed, not done, with the time it took", "[gc-send][flavour]") {
  // Issue 41: after Klipper's shutdown the progress line said "done" and
  // the summary "time 0.000 s, 0 lines/s".
  const std::string& file = pieces_of(kFlavours[1].fixture);
  auto r = gctest::run(quote(tool_path("gc-send")) + " --port virtual:" + printer(kFlavours[1]) +
                       ",simulated-clock,halt-after=300 " + quote(file));
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(r.err.find("the printer reported a fatal error: Klipper state: Shutdown") != std::string::npos);
  CHECK(r.err.find("gc-send: failed ") != std::string::npos);
  CHECK(r.err.find("gc-send: done ") == std::string::npos);
  const std::size_t summary = r.err.find("summary: lines ");
  REQUIRE(summary != std::string::npos);
  CHECK(number_after(r.err.substr(summary), "summary: lines ") >= 300);
  CHECK(number_after(r.err.substr(summary), ", time ") > 0);
}

namespace {

// Whether an executed command moved an axis or the extruder (a refused move
// is not in the log; a feed-rate-only G1 or a pace probe moves nothing).
bool moves(const std::string& command) {
  if (command.rfind("G1 ", 0) != 0 && command.rfind("G0 ", 0) != 0) return false;
  for (const char* axis : {" X", " Y", " Z", " E"})
    if (command.find(axis) != std::string::npos) return true;
  return false;
}

// A run on a printer that cannot move where the file says: status 1, the
// reason, "failed"; after `from` (a log index) nothing moved, and the
// print ended with the cancel G-code (heaters and motors off).
void check_stopped_unhomed(const gctest::RunResult& r, const std::vector<gctest::Executed>& log, std::size_t from,
                           const std::string& why) {
  CHECK(r.status == 1);
  CHECK(r.err.find(why) != std::string::npos);
  CHECK(r.err.find("the print stops after input line ") != std::string::npos);
  CHECK(r.err.find("gc-send: failed ") != std::string::npos);
  CHECK(r.err.find("gc-send: done ") == std::string::npos);
  CHECK(r.err.find("to go on with it") == std::string::npos);  // heaters off: nothing to resume
  REQUIRE(log.size() >= from + 5);
  for (std::size_t i = from; i < log.size(); ++i) {
    INFO(log[i].command);
    CHECK_FALSE(moves(log[i].command));
  }
  std::vector<std::string> tail;
  for (std::size_t i = log.size() - 5; i < log.size(); ++i) tail.push_back(log[i].command);
  CHECK(tail == std::vector<std::string>{"M104 S0", "M140 S0", "M107", "M84", "M400"});
}

}  // namespace

TEST_CASE("gc-send on Klipper: a homing that fails stops the print with heaters and motors off, status 1",
          "[gc-send][flavour]") {
  // Klipper answers a G28 whose endstop never triggered with "!! No trigger
  // on x after full movement" and its ok, and refuses every move after it:
  // streaming on would heat for the length of the print and end "done".
  std::string dir = gctest::temp_dir();
  std::string log = dir + "/executed.log", journal = dir + "/print.journal";
  auto r = gctest::run(quote(tool_path("gc-send")) + " --journal " + quote(journal) + " --port virtual:" +
                       printer(kFlavours[1]) + ",simulated-clock,home-fails,log=" + log + " " +
                       quote(pieces_of(kFlavours[1].fixture)));
  INFO(r.err);
  auto executed = gctest::read_log(log);
  std::size_t g28 = 0;
  while (g28 < executed.size() && executed[g28].command.rfind("G28", 0) != 0) ++g28;
  REQUIRE(g28 < executed.size());
  check_stopped_unhomed(r, executed, g28,
                        "homing failed: the printer answered G28 with \"No trigger on x after full movement\"");
}

TEST_CASE("gc-send on Klipper: homing lost mid-print (motors switched off) stops the print, status 1",
          "[gc-send][flavour]") {
  std::string dir = gctest::temp_dir();
  std::string log = dir + "/executed.log";
  auto r = gctest::run(quote(tool_path("gc-send")) + " --port virtual:" + printer(kFlavours[1]) +
                       ",simulated-clock,unhome-after=600,log=" + log + " " + quote(pieces_of(kFlavours[1].fixture)));
  INFO(r.err);
  auto executed = gctest::read_log(log);
  // The printer's 600 commands are the handshake's M110 and M115 (not in
  // read_log's list) and 598 of the file's: moves ran up to there, none after.
  const std::size_t unhomed = 600 - 2;
  REQUIRE(executed.size() > unhomed);
  bool moved_before = false;
  for (std::size_t i = 0; i < unhomed; ++i) moved_before = moved_before || moves(executed[i].command);
  CHECK(moved_before);
  check_stopped_unhomed(r, executed, unhomed, "the printer lost its homing (\"Must home axis first: ");
}

TEST_CASE("gc-send on Marlin: a homing that fails is its kill(), a fatal error", "[gc-send][flavour]") {
  // Marlin's VALIDATE_HOMING_ENDSTOPS (on by default): kill(), "Printer halted", then silence.
  std::string dir = gctest::temp_dir();
  std::string log = dir + "/executed.log";
  auto r = gctest::run(quote(tool_path("gc-send")) + " --port virtual:" + printer(kFlavours[0]) +
                       ",simulated-clock,home-fails,log=" + log + " " + quote(pieces_of(kFlavours[0].fixture)));
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(r.err.find("the printer reported a fatal error: Printer halted. kill() called!") != std::string::npos);
  auto executed = gctest::read_log(log);
  REQUIRE_FALSE(executed.empty());
  CHECK(executed.back().command.rfind("G28", 0) == 0);  // nothing ran after it
}

TEST_CASE("gc-send on Prusa: its own pause (M601) and M600 wait for the user, no timeout however long",
          "[gc-send][flavour]") {
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/own_pause.gcode", log = dir + "/executed.log";
  // gc-pause-at puts Prusa's M601 after layer 1; an M600 follows in layer 2.
  REQUIRE(gctest::run(quote(tool_path("gc-pause-at")) + " --after-layer 1 --method M601 --bed 250x210 " +
                      quote(pieces_of(kFlavours[2].fixture)) + " | awk '/^;LAYER_CHANGE/ { if (++n == 3) print \"M600\" } "
                      "{ print }' > " + quote(file))
              .status == 0);
  // The user takes 60 printer seconds for each, three seconds of gc-send's
  // (simulated) clock; the timeout is a quarter of one.
  auto r = gctest::run(quote(tool_path("gc-send")) + " -v --timeout 0.25 --port virtual:firmware=prusa,time-scale=20,"
                       "instant-moves,heat-rate=1000,user-seconds=60,simulated-clock,log=" + log + " " + quote(file));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find("printer action: paused") != std::string::npos);
  CHECK(r.err.find("printer action: resumed") != std::string::npos);
  CHECK(r.err.find("no timeout meanwhile") != std::string::npos);
  CHECK(r.err.find("timeouts 0") != std::string::npos);
  auto input = gctest::commands_of(gctest::read_file(file));
  auto executed = gctest::read_log(log);
  REQUIRE(executed.size() == input.size() + 1);
  for (std::size_t i = 0; i < input.size(); ++i) REQUIRE(executed[i].command == input[i].text);
  // The printer held everything after M601 until the user resumed.
  std::size_t m601 = 0;
  while (executed[m601].command != "M601") ++m601;
  CHECK(executed[m601 + 1].time - executed[m601 - 1].time >= 60);
}

TEST_CASE("gc-send through gc-virtual-printer --firmware klipper on a pty: exact, detected", "[gc-send][flavour]") {
  const std::string& file = pieces_of(kFlavours[1].fixture);
  gctest::PtyRun r = gctest::send_through_pty(file, "-v", "--firmware klipper --no-link-report --time-scale 1000 "
                                                       "--instant-moves --heat-rate 1000");
  INFO(r.result.err);
  CHECK(r.result.err.find("(flavour klipper)") != std::string::npos);
  // Its oks come as soon as a move is queued: holding moves to a planner
  // model would only slow it to the file's feed rates (78 s here, not 1).
  CHECK(r.result.err.find("pacing off") != std::string::npos);
  gctest::require_exact(r, gctest::commands_of(gctest::read_file(file)));
}

TEST_CASE("gc-send on OctoPrint's virtual printer with gc-send's defaults: 3000 moves in 10 s, nothing lost", "[gc-send][flavour]") {
  // Issue 41: its 64-byte receive buffer (a write waits for room, for up
  // to 10 s) and its scripted refusals of lines 100 to 115, with no
  // --rx-buffer: 2983 lines in 4.47 s on the simulated clock, no stall.
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/moves.gcode", log = dir + "/executed.log";
  REQUIRE(gctest::run(quote(tool_path("gc-subdivide")) + " --max 0.2 " +
                      quote(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")) +
                      " | awk 'BEGIN { print \"G28\"; print \"G90\"; print \"M83\" } /^;LAYER_CHANGE/ { on = 1 } "
                      "on && k++ < 3000' > " + quote(file))
              .status == 0);
  auto r = gctest::run(quote(tool_path("gc-send")) + " --port virtual:octoprint,simulated-clock,log=" + log + " " +
                       quote(file));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find("timeouts 0") != std::string::npos);
  CHECK(r.err.find("bytes lost to overruns 0") != std::string::npos);
  const std::size_t summary = r.err.find("summary: lines ");
  REQUIRE(summary != std::string::npos);
  CHECK(number_after(r.err.substr(summary), ", time ") <= 10);
  // Every command once and in order (gc-send's own lines left out).
  auto input = gctest::commands_of(gctest::read_file(file));
  auto executed = gctest::read_log(log, &input);
  REQUIRE(executed.size() == input.size() + 1);
  for (std::size_t i = 0; i < input.size(); ++i) REQUIRE(executed[i].command == input[i].text);
  CHECK(executed.back().command == "M400");
}
