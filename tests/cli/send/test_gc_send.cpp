// gc-send against gc-virtual-printer through a real pseudo-terminal, on real
// subdivided slicer output: the commands the printer executed are exactly the
// input's, in order, for every flow mode at 250000 and 115200 baud, also with
// faults; a silent printer and a fatal error end with exit status 1.
#include <catch2/catch.hpp>

#include <set>
#include <string>

#include "control_run.hpp"
#include "pty_run.hpp"
#include "serial_check.hpp"
#include "test_support.hpp"

using gctest::quote;
using gctest::run;
using gctest::tool_path;
using gctest::PtyRun;
using gctest::send_through_pty;
using gctest::require_exact;

namespace {

// 20000 lines of a fixture cut into pieces of at most 0.5 mm by gc-subdivide,
// written once per test run.
const std::string& subdivided_file() {
  static std::string path;
  if (path.empty()) {
    std::string dir = gctest::temp_dir();
    path = dir + "/subdivided.gcode";
    auto r = run(quote(tool_path("gc-subdivide")) + " --max 0.5 " +
                 quote(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")) + " | head -n 20000 > " + quote(path));
    REQUIRE(r.status == 0);
  }
  return path;
}

}  // namespace

// Every flow mode at one baud rate: the executed commands equal the input's.
static void every_flow_mode(const char* baud) {
  const std::string& file = subdivided_file();
  auto expected = gctest::commands_of(gctest::read_file(file));
  REQUIRE(expected.size() > 15000);
  for (const char* flow : {"ping-pong", "window", "advanced-ok", "auto"}) {
    INFO(flow << " at " << baud);
    // Instant moves and a high time scale: the run takes as long as the
    // round trips through the pty (the planner is covered in simulated time
    // by tests/unit/serial/sender/test_sender.cpp).
    std::string printer = std::string("--time-scale 1000 --instant-moves --heat-rate 1000 --baud ") + baud;
    if (std::string(flow) != "window") printer += " --advanced-ok";
    PtyRun r = send_through_pty(file, std::string("-q --flow ") + flow + " --baud " + baud, printer);
    require_exact(r, expected);
  }
}

TEST_CASE("gc-send: 20000 subdivided lines through a pty at 250000 baud, every flow mode", "[gc-send]") {
  every_flow_mode("250000");
}

TEST_CASE("gc-send: 20000 subdivided lines through a pty at 115200 baud, every flow mode", "[gc-send]") {
  every_flow_mode("115200");
}

TEST_CASE("gc-send: corrupted lines, lost oks, busy stalls, spurious resends: nothing lost, duplicated or reordered",
          "[gc-send]") {
  const std::string& file = subdivided_file();
  auto expected = gctest::commands_of(gctest::read_file(file));
  std::string faults =
      "--fault corrupt=0.01 --fault drop-ok=0.005 --fault busy=0.001 --fault resend=0.002 --fault garbage=0.002";
  for (const char* flow : {"window", "advanced-ok"}) {
    INFO(flow);
    std::string printer = "--time-scale 1000 --instant-moves --heat-rate 1000 " + faults;
    if (std::string(flow) == "advanced-ok") printer += " --advanced-ok";
    // A lost ok is asked for as soon as it is overdue: no --timeout runs out.
    PtyRun r = send_through_pty(file, std::string("--flow ") + flow, printer);
    require_exact(r, expected);
    CHECK(r.result.err.find("resends 0,") == std::string::npos);
    CHECK(r.result.err.find(", timeouts 0") != std::string::npos);
  }
}

TEST_CASE("gc-send: a printer that stops answering: exit 1 naming the last acknowledged line and layer", "[gc-send]") {
  const std::string& file = subdivided_file();
  auto expected = gctest::commands_of(gctest::read_file(file));
  PtyRun r = send_through_pty(file, "--timeout 0.2 --max-timeouts 2",
                              "--time-scale 200 --heat-rate 1000 --fault silent-after=3000");
  CHECK(r.result.status == 1);
  INFO(r.result.err);
  CHECK(r.result.err.find("gc-send: the printer stopped answering") != std::string::npos);
  gctest::ExecutedLog log = r.log;
  gctest::drop_own_lines(log, expected);
  REQUIRE_FALSE(log.numbers.empty());
  // The last executed line's ok went out before the printer fell silent
  // (gc-send's own lines after it name it too).
  std::size_t last = log.commands.size();
  std::string where = "last acknowledged: line " + std::to_string(expected[last - 1].source_line) + " of the input (layer ";
  CHECK(r.result.err.find(where) != std::string::npos);
}

TEST_CASE("gc-send: a fatal printer error stops sending with exit 1", "[gc-send]") {
  const std::string& file = subdivided_file();
  PtyRun r = send_through_pty(file, "", "--time-scale 200 --heat-rate 1000 --fault halt-after=2000");
  CHECK(r.result.status == 1);
  CHECK(r.result.err.find("fatal error: Thermal Runaway") != std::string::npos);
  CHECK(r.log.commands.size() < 2000);
}

TEST_CASE("gc-send: the built-in virtual printer, host commands kept back, summary", "[gc-send]") {
  std::string dir = gctest::temp_dir();
  std::string log = dir + "/log";
  // (@pause pauses the host: tests/cli/send/test_gc_send_pause.cpp.)
  std::string input = "; a comment\nG28\n\n@notify done\nG1 X10 Y10 F6000 ; move\nN5 G1 X20*99\nM110 N7\nM105\n";
  auto r = run(quote(tool_path("gc-send")) + " -v --port virtual:time-scale=50,log=" + log, input);
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(r.err.find("host command '@notify done' not sent") != std::string::npos);
  CHECK(r.err.find("M110 not sent") != std::string::npos);
  CHECK(r.err.find("gc-send: summary: lines 5,") != std::string::npos);
  auto executed = gctest::parse_executed_log(gctest::read_file(log));
  CHECK(executed.commands == std::vector<std::string>{"G28", "G1 X10 Y10 F6000", "G1 X20", "M105", "M400"});
}

TEST_CASE("gc-send: Ctrl-C stops, a second Ctrl-C sends M112", "[gc-send]") {
  std::string file = gctest::fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode");
  std::string dir = gctest::temp_dir();
  std::string err = quote(dir + "/err"), log = quote(dir + "/executed.log");
  // The first Ctrl-C once the printer has run 30 commands (heated at once,
  // then moves in real time: the safe end's park takes seconds), the second
  // once gc-send says it is cancelling. Fixed sleeps (0.5 s, then 0.1 s)
  // failed on a loaded machine: the first came before the print had begun,
  // or the second after the safe end had finished (exit 0 both times).
  std::string script = quote(tool_path("gc-send")) + " --port virtual:heat-rate=1000,log=" + log + " " +
                       quote(file) + " 2>" + err + " & p=$!\n" +
                       gctest::wait_for_lines(log, {.at_least = "30", .while_alive = "$p", .tries = 5000, .every = 0.002}) +
                       "kill -INT $p\n" +
                       gctest::wait_for_lines(err, {.match = "'press Ctrl-C again'",
                                                    .while_alive = "$p",
                                                    .tries = 5000,
                                                    .every = 0.002}) +
                       "kill -INT $p; wait $p; s=$?; cat " + err + " >&2; exit $s";
  auto r = run(script);
  INFO(r.err);
  CHECK(r.status == 130);
  CHECK(r.err.find("emergency stop: M112 sent") != std::string::npos);
}

TEST_CASE("gc-send: usage errors exit 2, --list-ports works without hardware", "[gc-send]") {
  CHECK(run(quote(tool_path("gc-send")) + " --flow fast").status == 2);
  CHECK(run(quote(tool_path("gc-send")) + " --port virtual:warp=9").status == 2);
  CHECK(run(quote(tool_path("gc-send")) + " --baud 0").status == 2);
  CHECK(run(quote(tool_path("gc-send")) + " --list-ports").status == 0);
  auto r = run(quote(tool_path("gc-send")) + " --port /nonexistent/tty", "G28\n");
  CHECK(r.status == 1);
  CHECK(r.err.find("gc-send: cannot open /nonexistent/tty") != std::string::npos);
  CHECK(run(quote(tool_path("gc-virtual-printer")) + " --link").status == 2);
}

namespace {

// gc-send's time for `file` on the in-process printer on the simulated
// clock (virtual:simulated-clock): the same on a loaded machine.
double simulated_seconds(const std::string& file, const std::string& printer) {
  auto r = run(quote(tool_path("gc-send")) + " --no-pace --port virtual:simulated-clock," + printer + " " + quote(file));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find(", timeouts 0") != std::string::npos);
  const std::size_t summary = r.err.find("summary: lines ");
  REQUIRE(summary != std::string::npos);
  return gctest::number_after(r.err.substr(summary), ", time ");
}

// The input lines gc-send sends, in the order the printer executed them.
std::vector<std::string> executed_of(const PtyRun& r) { return r.log.commands; }

}  // namespace

TEST_CASE("gc-send: 3000 short moves at 250000 baud with faults are exact with no timeout within 3 times the clean run",
          "[gc-send]") {
  // 0.2 mm pieces from the middle of a print; moves take no time, so the
  // link and the recovery from faults are all that counts. Time scale 2
  // keeps the test short; the figures in docs/gc-send-faults.md are at time scale 1.
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/moves.gcode";
  auto r = run(quote(tool_path("gc-subdivide")) + " --max 0.2 " +
               quote(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")) + " | sed -n 2001,5000p > " +
               quote(file));
  REQUIRE(r.status == 0);
  auto expected = gctest::commands_of(gctest::read_file(file));
  REQUIRE(expected.size() > 2900);
  std::string printer = "--time-scale 2 --instant-moves";
  std::string faults =
      " --fault corrupt=0.01 --fault drop-ok=0.002 --fault garbage=0.002 --fault resend=0.002 --fault seed=3";
  // (--no-pace: pacing sends no probe on a link that has garbled a line,
  // so a paced faulty run would measure the pacer's fallback, a move per
  // answer, against a clean run fed at the link's speed, not the recovery.)
  PtyRun clean = send_through_pty(file, "--no-pace", printer);
  PtyRun faulty = send_through_pty(file, "--no-pace", printer + faults);
  require_exact(clean, expected);
  require_exact(faulty, expected);
  INFO(faulty.result.err);
  CHECK(faulty.result.err.find("resends 0,") == std::string::npos);
  CHECK(faulty.result.err.find(", timeouts 0") != std::string::npos);
  // The time the recovery costs, on the simulated clock (a pty's wall
  // times move with the machine's load): the same faults in process.
  const std::string model = "time-scale=2,instant-moves";
  double t_clean = simulated_seconds(file, model);
  double t_faulty = simulated_seconds(file, model + ",corrupt=0.01,drop-ok=0.002,garbage=0.002,resend=0.002,seed=3");
  INFO("faulty " << t_faulty << " s, clean " << t_clean << " s (simulated)");
  CHECK(t_faulty < 3 * t_clean);
}

TEST_CASE("gc-send: an over-long M117 is shortened and an over-long line stops the print before it without a stall",
          "[gc-send]") {
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/long.gcode";
  std::string glued;
  while (glued.size() < 33000) glued += "G1 X10.123 Y20.456 E0.01234 ";
  gctest::write_file(file, "G28\nM117 " + std::string(150, 'x') + "\nG1 X10 F3000\n" + glued +
                               "\nG1 X20\n");
  PtyRun r = send_through_pty(file, "", "--time-scale 100 --heat-rate 1000");
  INFO(r.result.err);
  CHECK(r.result.status == 1);
  CHECK(r.result.err.find("gc-send: line 2: warning: M117 message shortened to 88 bytes") != std::string::npos);
  CHECK(r.result.err.find("gc-send: line 4: the line is 33") != std::string::npos);
  CHECK(r.result.err.find("not sent: printing stopped before it (--skip-bad-lines leaves such lines out)") !=
        std::string::npos);
  CHECK(r.result.err.find("timeouts 0") != std::string::npos);
  CHECK(executed_of(r) == std::vector<std::string>{"G28", "M117 " + std::string(83, 'x'), "G1 X10 F3000", "M400"});
  // With --skip-bad-lines the print goes on after it.
  PtyRun s = send_through_pty(file, "--skip-bad-lines", "--time-scale 100 --heat-rate 1000");
  CHECK(s.result.status == 0);
  CHECK(executed_of(s) ==
        std::vector<std::string>{"G28", "M117 " + std::string(83, 'x'), "G1 X10 F3000", "G1 X20", "M400"});
  // A printer that keeps more takes it whole.
  PtyRun t = send_through_pty(file, "--max-line 200", "--time-scale 100 --heat-rate 1000 --max-line 200");
  CHECK(t.result.status == 1);
  CHECK(executed_of(t).at(1) == "M117 " + std::string(150, 'x'));
}

TEST_CASE("gc-send: without --max-line the limit reported in M115 applies", "[gc-send]") {
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/msg.gcode";
  gctest::write_file(file, "M117 " + std::string(60, 'y') + "\n");
  PtyRun r = send_through_pty(file, "", "--time-scale 100 --max-line 40");
  INFO(r.result.err);
  CHECK(r.result.status == 0);
  CHECK(executed_of(r) == std::vector<std::string>{"M117 " + std::string(27, 'y'), "M400"});
}

TEST_CASE("gc-send: binary junk is refused with its line number or left out with --skip-bad-lines", "[gc-send]") {
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/junk.gcode";
  // A PNG header glued into the G-code.
  static const char kJunk[] = "G28\nG1 X5 F3000\n\x89PNG\r\x1a\n\x00\x00\x00\rIHDR\nG1 X6\n";
  gctest::write_file(file, std::string(kJunk, sizeof kJunk - 1));
  PtyRun r = send_through_pty(file, "", "--time-scale 100 --heat-rate 1000");
  INFO(r.result.err);
  CHECK(r.result.status == 1);
  CHECK(r.result.err.find("gc-send: line 3: byte 0x89 at column 1 is not G-code text") != std::string::npos);
  CHECK(executed_of(r) == std::vector<std::string>{"G28", "G1 X5 F3000", "M400"});
  PtyRun s = send_through_pty(file, "--skip-bad-lines", "--time-scale 100 --heat-rate 1000");
  CHECK(s.result.status == 0);
  CHECK(s.result.err.find("gc-send: line 4: warning: byte 0x00 at column 1") != std::string::npos);
  CHECK(s.result.err.find("left out 2") != std::string::npos);
  CHECK(executed_of(s) == std::vector<std::string>{"G28", "G1 X5 F3000", "G1 X6", "M400"});
}

TEST_CASE("gc-send: an empty input or one without a command prints nothing and exits 1", "[gc-send]") {
  for (const char* input : {"", "; sliced by nothing\n\n   \n"}) {
    auto r = run(quote(tool_path("gc-send")) + " --port virtual:time-scale=100", input);
    CHECK(r.status == 1);
    CHECK(r.err.find("gc-send: nothing was printed: the input has no G-code command") != std::string::npos);
  }
}

TEST_CASE("gc-send: a pseudo-terminal without a reported baud rate is an unlimited link", "[gc-send]") {
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/moves.gcode";
  gctest::write_file(file, "G1 X10 F6000\nG1 X20\nG1 X30\n");
  PtyRun r = send_through_pty(file, "", "--time-scale 100 --no-link-report");
  INFO(r.result.err);
  CHECK(r.result.status == 0);
  CHECK(r.result.err.find("link unlimited (pseudo-terminal)") != std::string::npos);
  CHECK(r.result.err.find("utilisation") == std::string::npos);
  // With the simulated rate reported, the utilisation is against it.
  PtyRun s = send_through_pty(file, "", "--time-scale 100");
  CHECK(s.result.err.find("link utilisation ") != std::string::npos);
  CHECK(s.result.err.find("(250000 baud, time scale 100)") != std::string::npos);
}

TEST_CASE("gc-send: --help and the man page name the same options", "[gc-send]") {
  auto help = run(quote(tool_path("gc-send")) + " --help");
  REQUIRE(help.status == 0);
  std::string man = gctest::read_file(std::string(GC_FIXTURES_DIR) + "/../../man/gc-send.1");
  // Examples also run other tools (gc-subdivide --max, gc-virtual-printer --link).
  std::string help_options = help.out.substr(help.out.find("Options:"));
  std::string man_options = man.substr(0, man.find(".SH EXAMPLES"));
  std::set<std::string> in_help = gctest::long_options(help_options);
  CHECK(in_help == gctest::long_options(man_options));
  CHECK(in_help.count("--max-line") == 1);
  CHECK(in_help.count("--skip-bad-lines") == 1);
}

TEST_CASE("gc-send: the default flow uses ADVANCED_OK where the answers carry it, the window otherwise", "[gc-send]") {
  // Issue 41: with the window as default, a Marlin answering "ok N.. P.. B.."
  // was paced at 65 s against 59 unpaced (134 against 47 on a busy host).
  std::string input = "G28\nG1 X10 Y10 F6000\nG1 X20\nG1 X30\n";
  for (const char* printer : {"advanced-ok,", ""}) {
    auto r = run(quote(tool_path("gc-send")) + " --port virtual:" + printer + "time-scale=50,instant-moves", input);
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK(r.err.find(std::string("flow ") + (*printer != '\0' ? "advanced-ok" : "window") + ",") != std::string::npos);
  }
}
