// gc-send against gc-virtual-printer resetting mid-print (its greeting in
// each form, at chosen moments, after a reconnect, while paused): the print
// comes back with the resume sequence and finishes. The printer's executed
// log across the sessions holds every input command once, except the re-run
// after the reset, at most what the printer buffers (its planner's 16 moves
// and its queue's 4 commands); no Z homing after the
// first layer; every X/Y move of the sequence above what was printed; bed
// and hot end at their targets before anything is extruded; the re-run
// moves end where they did the first time, E included. A delta is refused
// with the gc-relayer recipe, nothing more sent.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>

#include "gcode/core/line.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/serial/journal/journal.hpp"
#include "gcode/serial/journal/journal_point.hpp"
#include "pty_run.hpp"
#include "reset_check.hpp"
#include "test_support.hpp"

using gctest::PtyRun;
using gctest::quote;
using gctest::run;
using gctest::require_resumed;
using gctest::send_through_pty;
using gctest::tool_path;

namespace {

// The first 9000 lines of a real slicer file (relative E, z-hop) cut into
// 0.2 mm pieces: the start code, layer 1 and the start of layer 2.
const std::string& reset_pieces() { return gctest::pieces_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 9000); }

// Absolute E (a G92 E must put E back exactly), Cura's 5 mm retractions.
const std::string& absolute_file() { return gctest::pieces_of("cura_cube_0.2_abs_zhop_skirt.gcode", 6000); }

}  // namespace

TEST_CASE("gc-send: a printer reset mid-layer, at a layer change or in the start code comes back and finishes, its greeting whole or after a cut line",
          "[gc-send][reset]") {
  auto expected = gctest::commands_of(gctest::read_file(reset_pieces()));
  struct Moment {
    const char* fault;
    const char* greeting;
    const char* says;
  };
  // "cut": the board resets while it sends an ok, its greeting follows the
  // half that went out ("ostart"); early in the print the printer's
  // "Resend: 1" is no sign of a reset, only the greeting is.
  for (Moment m : {Moment{"reset@line=3000", "start", "going back to line "},
                   Moment{"reset@layer=2", "start", "going back to line "},
                   Moment{"reset@line=4", "start", "before anything was printed; starting the print again"},
                   Moment{"reset@line=4", "cut", "before anything was printed; starting the print again"},
                   Moment{"reset@line=3000", "cut", "going back to line "}}) {
    PtyRun r = send_through_pty(reset_pieces(), "--no-journal",
                                gctest::kFastPrinter + "--fault " + m.fault + " --greeting " + m.greeting);
    INFO(m.fault << " " << m.greeting << ": " << r.result.err);
    REQUIRE(r.result.status == 0);
    CHECK(r.result.err.find("the printer reset (it said \"start\")") != std::string::npos);
    CHECK(r.result.err.find(m.says) != std::string::npos);
    gctest::ResetFigures f = require_resumed(r.log_text, expected);
    CHECK(f.resets == 1);
    CHECK(r.result.err.find("printer resets 1 (") != std::string::npos);  // the summary
    if (std::string(m.fault) != "reset@line=4") {
      CHECK(r.result.err.find("may print twice") != std::string::npos);
      CHECK(f.redone_moves > 0);
    }
  }
}

TEST_CASE("gc-send: each form of the greeting is a reset, an absolute-E print gets its E back exactly",
          "[gc-send][reset]") {
  auto expected = gctest::commands_of(gctest::read_file(absolute_file()));
  for (const char* greeting : {"nul", "twice", "external", "cut"}) {
    PtyRun r = send_through_pty(absolute_file(), "--no-journal",
                                gctest::kFastPrinter + "--greeting " + greeting + " --fault reset@line=4000");
    INFO(greeting << ": " << r.result.err);
    REQUIRE(r.result.status == 0);
    gctest::ResetFigures f = require_resumed(r.log_text, expected);
    CHECK(f.redone_moves > 0);
    CHECK(f.redone_mm < 20 * 0.2 + 1e-6);
  }
}

TEST_CASE("gc-send: a printer that restarted while its port was away comes back after the reconnect",
          "[gc-send][reset][reconnect]") {
  auto expected = gctest::commands_of(gctest::read_file(reset_pieces()));
  PtyRun r = send_through_pty(reset_pieces(), "--no-journal --reconnect 30", gctest::kFastPrinter + "--fault drop-reset=50@line=2000");
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  CHECK(r.result.err.find("lost the printer's port") != std::string::npos);
  CHECK(r.result.err.find("while its port was away") != std::string::npos);
  CHECK(require_resumed(r.log_text, expected).resets == 1);
}

TEST_CASE("gc-send: a reset while paused resumes into the pause, the resume returns exactly", "[gc-send][reset][pause]") {
  auto expected = gctest::commands_of(gctest::read_file(reset_pieces()));
  std::string dir = gctest::temp_dir();
  std::string status = dir + "/status.json", fifo = dir + "/control";
  auto wait_for = [&](const std::string& state) {
    return gctest::wait_for_lines(quote(status), {.match = quote("\"" + state + "\"")});
  };
  std::string during = gctest::wait_for_fifo(fifo) + "sleep 0.15; echo pause > " + quote(fifo) + "\n" + wait_for("paused") +
                       "kill -USR1 $vp; sleep 0.3\n" + wait_for("paused") + "echo resume > " + quote(fifo);
  PtyRun r = send_through_pty(reset_pieces(),
                              "--no-journal --rush 1 --status-file " + quote(status) + " --control " + quote(fifo) +
                                  " --progress-interval 0.05",
                              gctest::kFastPrinter, during);
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  CHECK(r.result.err.find("the printer reset") != std::string::npos);
  require_resumed(r.log_text, expected, 20, true);
  // The status file says it too.
  std::string json = gctest::read_file(status);
  CHECK(json.find("\"resets\": 1") != std::string::npos);
  CHECK(json.find("\"redone_mm\": 0.0") == std::string::npos);
}

TEST_CASE("gc-send --delta: a reset stops the print with the gc-relayer recipe, nothing more sent",
          "[gc-send][reset]") {
  PtyRun r = send_through_pty(reset_pieces(), "--no-journal --delta", gctest::kFastPrinter + "--fault reset@line=3000");
  INFO(r.result.err);
  CHECK(r.result.status == 1);
  CHECK(r.result.err.find("cannot home X and Y without Z") != std::string::npos);
  CHECK(r.result.err.find("gc-relayer --resume-from-z") != std::string::npos);
  auto log = gctest::read_reset_log(r.log_text);
  REQUIRE(log.sessions.size() == 2);
  CHECK(log.sessions[1].empty());  // not a numbered line after the reset
}

namespace {

// gc-virtual-printer on a pty in `dir` (`$vp`, with `printer_args`),
// gc-send killed with SIGKILL once the shell snippet `kill_when` returns,
// then `then` (a shell script: $gs is what runs next).
gctest::RunResult killed_when(const std::string& dir, const std::string& input, const std::string& kill_when,
                              const std::string& then, const std::string& resume_args = "",
                              const std::string& printer_args = "--heat-rate 1000") {
  std::string port = dir + "/printer", journal = dir + "/print.journal";
  std::string send = quote(tool_path("gc-send")) + " --port " + quote(port) + " --journal " + quote(journal);
  std::string script =
      quote(tool_path("gc-virtual-printer")) + " -q --time-scale 20 " + printer_args + " --link " +
      quote(port) + " --log " + quote(dir + "/executed.log") + " & vp=$!\n" +
      gctest::wait_for_link(port) + send + " -q " +
      quote(input) + " 2>/dev/null & gs=$!\n" + kill_when + "\nkill -9 $gs; wait $gs 2>/dev/null\n" + then + "\n" +
      send + " " + resume_args + " --resume " + quote(journal) + " " + quote(input) + " & gs=$!\n" +
      "wait $gs; s=$?; kill $vp; wait $vp; exit $s";
  return run(script);
}

// Waits until gc-send's status file says paused, or gc-send ($gs) ended.
std::string wait_paused(const std::string& status) {
  return gctest::wait_for_lines(quote(status), {.match = quote("\"paused\""), .while_alive = "$gs"});
}

// ... killed `seconds` after the printer acknowledged its first line (by
// the journal): a loaded machine can take a second to start gc-send, and a
// gc-send killed before its journal holds anything leaves nothing to resume.
gctest::RunResult killed_then(const std::string& dir, const std::string& input, double seconds,
                              const std::string& then, const std::string& resume_args = "") {
  return killed_when(dir, input, gctest::wait_for_journal_start(dir + "/print.journal", "$gs") + "sleep " +
                                     std::to_string(seconds), then, resume_args);
}

// gc-send (`send_args`, a status file and a control FIFO in `dir`) prints
// on gc-virtual-printer (`printer_args`) until `pause now` goes to its FIFO;
// it is killed with SIGKILL once the shell snippet `kill_when` returns,
// `between` runs, and gc-send --resume goes on, told `resume` once it says
// it is paused.
gctest::RunResult killed_while_pausing(const std::string& dir, const std::string& send_args,
                                       const std::string& printer_args, const std::string& kill_when,
                                       const std::string& between) {
  std::string status = dir + "/status.json", fifo = dir + "/control", port = dir + "/printer",
              journal = dir + "/print.journal";
  std::string send = quote(tool_path("gc-send")) + " --port " + quote(port) + " --journal " + quote(journal) + " " +
                     send_args + " --status-file " + quote(status) + " --control " + quote(fifo) + " ";
  std::string script =
      quote(tool_path("gc-virtual-printer")) + " -q --time-scale 20 " + printer_args + " --link " + quote(port) +
      " --log " + quote(dir + "/executed.log") + " & vp=$!\n" +
      gctest::wait_for_link(port) + send + " -q " +
      quote(reset_pieces()) + " 2>/dev/null & gs=$!\n" + gctest::wait_for_fifo(fifo) +
      // In layer 1, however late a loaded machine started gc-send (a pause in
      // the start code, before anything was extruded, is another case).
      gctest::wait_for_lines(quote(status), {.match = quote("\"layer\": 1,")}) +
      "sleep 0.5; echo pause now > " + quote(fifo) + "\n" + kill_when +
      "\nkill -9 $gs; wait $gs 2>/dev/null; rm -f " + quote(status) + "\n" + between + "\n" + send + " --resume " +
      quote(journal) + " " + quote(reset_pieces()) + " & gs=$!\n" + wait_paused(status) +
      "kill -0 $gs && timeout 10 sh -c 'echo resume > " + quote(fifo) + "'\n" +
      "wait $gs; s=$?; kill $vp; wait $vp; exit $s";
  return run(script);
}

}  // namespace

TEST_CASE("gc-send --resume after kill -9 and a printer reset: back to the print, every command once but the re-run",
          "[gc-send][reset][resume]") {
  auto expected = gctest::commands_of(gctest::read_file(reset_pieces()));
  std::string dir = gctest::temp_dir();
  // The reset comes while the printer still drains what it took.
  auto r = killed_then(dir, reset_pieces(), 2, "kill -USR1 $vp; sleep 0.3");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find("resuming: the printer reset since the print stopped (it greeted again); going back to input "
                   "line ") != std::string::npos);
  CHECK(r.err.find("may print twice") != std::string::npos);
  CHECK(require_resumed(gctest::read_file(dir + "/executed.log"), expected).resets == 1);
}

TEST_CASE("gc-send --resume after kill -9: a reset in the resumed print comes back too",
          "[gc-send][reset][resume]") {
  auto expected = gctest::commands_of(gctest::read_file(reset_pieces()));
  // (The resumed gc-send runs in the background meanwhile: `then` starts a
  // subshell that resets the printer once it has run `after` commands of
  // the resumed print. Fewer than its planner holds: the way back is the
  // command the resume went on after, which only the journal knew. Numbered
  // commands only: the resume's questions first (M400, M114) are not the
  // print's, and a reset among them is another test's case.)
  for (int after : {1, 8, 150}) {
    INFO("reset " << after << " commands into the resumed print");
    std::string dir = gctest::temp_dir();
    const std::string log = quote(dir + "/executed.log");
    auto r = killed_then(dir, reset_pieces(), 1.5,
                         "sleep 0.3; n0=$(" + gctest::numbered_log_count(dir + "/executed.log") + ")\n(" +
                             gctest::wait_for_lines(log, {.match = gctest::numbered_log_line(),
                                                          .at_least = "$((n0 + " + std::to_string(after) + "))",
                                                          .tries = 150000,
                                                          .every = 0.002}) +
                             "kill -USR1 $vp) &");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.err.find("resuming: the printer kept running") != std::string::npos);
    CHECK(r.err.find("the printer reset (it said \"start\")") != std::string::npos);
    CHECK(require_resumed(gctest::read_file(dir + "/executed.log"), expected).resets == 1);
  }
}

TEST_CASE("gc-send --resume killed as its new journal lands, then a printer reset: the next resume goes back to "
          "where that one went on, nothing redone",
          "[gc-send][reset][resume]") {
  auto expected = gctest::commands_of(gctest::read_file(reset_pieces()));
  std::string dir = gctest::temp_dir();
  const std::string journal = quote(dir + "/print.journal");
  const std::string inode = "stat -c %i " + journal + " 2>/dev/null";
  // The second gc-send is killed as soon as its journal is in place (a new
  // file renamed over the old), before it has sent a line; the printer had
  // kept running, then it resets.
  const std::string second = "i0=$(" + inode + ")\n" + quote(tool_path("gc-send")) + " -q --port " +
                             quote(dir + "/printer") + " --resume " + journal + " " + quote(reset_pieces()) +
                             " 2>/dev/null & gs=$!\n" +
                             gctest::wait_until("[ \"$(" + inode + ")\" != \"$i0\" ] || ! kill -0 $gs", 5000, 0.001) +
                             "kill -9 $gs; wait $gs 2>/dev/null\ncp " + journal + " " + quote(dir + "/killed.journal") +
                             "\nkill -USR1 $vp; sleep 0.3";
  auto r = killed_then(dir, reset_pieces(), 1.5, second);
  INFO(r.err);
  REQUIRE(r.status == 0);
  // It once held its header alone there: "holds no command".
  gcode::serial::JournalContents killed = gcode::serial::read_journal(dir + "/killed.journal");
  CHECK_FALSE(killed.entries.empty());
  CHECK(killed.acknowledged > 0);
  CHECK(r.err.find("resuming: the printer reset since the print stopped (it greeted again); going back to input "
                   "line ") != std::string::npos);
  // The second run's M400 had drained the printer: what ran before is not
  // printed twice. That holds when the kill came before the printer
  // acknowledged a line past the drained one; a kill the shell's poll made
  // late (a loaded machine, a sanitizer build) lets moves through, and those
  // may print twice, as the message then says.
  std::uint64_t drained = 0;
  for (const gcode::serial::JournalEntry& e : killed.entries)
    if (gcode::serial::is_drained(e.point)) drained = e.n;
  CHECK(drained > 0);
  if (killed.acknowledged <= drained) {
    CHECK(r.err.find(", 0 moves (0.0 mm) may print twice") != std::string::npos);
  } else {
    CHECK(r.err.find(" may print twice") != std::string::npos);
  }
  CHECK(require_resumed(gctest::read_file(dir + "/executed.log"), expected).resets == 1);
}

namespace {

// Waits until the printer acknowledged `lines` lines after the journal's
// first record matching `marker` (restore=[1-9]: the way back after a
// reset begins; paused=1: the pause block does).
std::string acknowledged_after(const std::string& dir, const std::string& marker, int lines) {
  const std::string journal = quote(dir + "/print.journal");
  return gctest::wait_for_lines(journal, {.match = "'^A '",
                                          .after = quote(marker),
                                          .at_least = std::to_string(lines),
                                          .tries = 5000,
                                          .every = 0.002});
}

std::string in_way_back(const std::string& dir, int lines) { return acknowledged_after(dir, "restore=[1-9]", lines); }

}  // namespace

TEST_CASE("gc-send killed inside the way back after a printer reset: --resume makes the way back again",
          "[gc-send][reset][resume]") {
  auto expected = gctest::commands_of(gctest::read_file(reset_pieces()));
  // gc-send is killed once the printer has acknowledged `after` lines of
  // the resume sequence (heating, G92 Z, lift, G28 X Y, travel, descent,
  // prime, modes; 0: as it goes out): the printer keeps running, and took
  // some of them last. (The bed heats slowly enough for the kill to come
  // inside the sequence.)
  int inside = 0;
  for (int after : {0, 1, 2, 3, 5}) {
    INFO("killed " << after << " lines into the way back");
    std::string dir = gctest::temp_dir();
    auto r = killed_when(dir, reset_pieces(), in_way_back(dir, after), "sleep 0.5", "",
                         "--heat-rate 100 --fault reset@line=2500");
    INFO(r.err);
    REQUIRE(r.status == 0);
    if (r.err.find("inside the way back after a reset; that way back again") != std::string::npos) ++inside;
    const std::string ran = gctest::read_file(dir + "/executed.log");
    REQUIRE(gctest::read_reset_log(ran).reset_at.size() == 1);
    CHECK(require_resumed(ran, expected).resets == 1);
  }
  CHECK(inside >= 3);
}

TEST_CASE("gc-send --resume of a print killed while paused goes back into the pause, the printer kept running or reset",
          "[gc-send][reset][resume][pause]") {
  auto expected = gctest::commands_of(gctest::read_file(reset_pieces()));
  for (bool reset : {false, true}) {
    INFO((reset ? "reset" : "kept running"));
    std::string dir = gctest::temp_dir();
    std::string status = dir + "/status.json";
    auto r = killed_while_pausing(dir, "--rush 1", "--heat-rate 1000", wait_paused(status) + "sleep 0.5",
                                  reset ? "kill -USR1 $vp; sleep 0.3" : "");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.err.find("the print was paused after input line ") != std::string::npos);
    gctest::ResetFigures f = require_resumed(gctest::read_file(dir + "/executed.log"), expected, 20, true);
    CHECK(f.resets == (reset ? 1 : 0));
    CHECK(f.redone_moves == 0);  // parked: every move before the pause had run
  }
}

namespace {

// Every input command in the printer's log (one session: it kept running)
// stands where the input alone takes the machine, X, Y, Z and E: lines of
// gc-send's own between them (a pause and its return) moved nothing for
// good, not even the filament.
void require_input_positions(const std::string& log_text, const std::vector<gctest::SentCommand>& expected) {
  gctest::ResetLog log = gctest::read_reset_log(log_text);
  REQUIRE(log.sessions.size() == 1);
  gcode::MachineState s;
  std::size_t k = 0;
  int checked = 0;
  for (const gctest::RanCommand& c : log.sessions[0]) {
    if (k == expected.size() || c.text != expected[k].text) continue;  // gc-send's own
    s.apply(gcode::Line::parse(expected[k++].text));
    INFO("input command " << k << ": " << c.text);
    const double at[] = {c.x, c.y, c.z, c.e};
    for (int a : {gcode::kX, gcode::kY, gcode::kZ, gcode::kE}) {
      if (!s.known[static_cast<std::size_t>(a)]) continue;
      CHECK(std::abs(s.position[a] - at[a]) < 1e-4);
      ++checked;
    }
  }
  CHECK(k == expected.size());
  CHECK(checked > 1000);
}

}  // namespace

TEST_CASE("gc-send --resume of a print killed inside its pause block: the rest of the block, parked, an exact return",
          "[gc-send][reset][resume][pause]") {
  auto expected = gctest::commands_of(gctest::read_file(reset_pieces()));
  // A long block (park, M400, messages, a beep) that goes out a little at a
  // time: a 40-byte window, a printer of one planner block and one queue
  // entry. gc-send is killed once `after` acknowledgements follow the
  // block's first record in the journal.
  int inside = 0;
  for (int after : {0, 2, 3, 4, 5}) {
    INFO("killed " << after << " acknowledgements into the pause block");
    std::string dir = gctest::temp_dir();
    auto r = killed_while_pausing(dir, "--park 20,180 --wait-moves --beep --host-message waiting --rx-buffer 40 --rush 1",
                                  "--heat-rate 1000 --planner 1 --queue 1", acknowledged_after(dir, "paused=1", after),
                                  "sleep 0.3");
    INFO(r.err);
    REQUIRE(r.status == 0);
    if (r.err.find("stopped inside the pause block: its ") != std::string::npos) ++inside;
    CHECK((r.err.find("the print was paused after input line ") != std::string::npos ||
           r.err.find("took none of the pause block") != std::string::npos));
    const std::string ran = gctest::read_file(dir + "/executed.log");
    CHECK(require_resumed(ran, expected, 20, true).resets == 0);
    require_input_positions(ran, expected);
    CHECK(ran.find("G1 X20 Y180") != std::string::npos);  // it parked
  }
  CHECK(inside >= 2);
}

TEST_CASE("gc-send: printer resets at seeded random moments: each print comes back and finishes",
          "[gc-send][reset]") {
  auto expected = gctest::commands_of(gctest::read_file(reset_pieces()));
  std::mt19937 rng(22);
  std::uniform_int_distribution<int> line(5, static_cast<int>(expected.size()) - 50);
  for (int round = 0; round < 4; ++round) {
    const std::string fault = "reset@line=" + std::to_string(line(rng));
    PtyRun r = send_through_pty(reset_pieces(), "--no-journal", gctest::kFastPrinter + "--fault " + fault);
    INFO(fault << ": " << r.result.err);
    REQUIRE(r.result.status == 0);
    CHECK(require_resumed(r.log_text, expected).resets == 1);
  }
}

TEST_CASE("gc-send --resume --delta after a reset: refused with the gc-relayer recipe, exit 1, nothing sent",
          "[gc-send][reset][resume]") {
  std::string dir = gctest::temp_dir();
  // The printer drains what it took, then resets.
  auto r = killed_then(dir, reset_pieces(), 1.5, "sleep 1; kill -USR1 $vp; sleep 0.3", "--delta");
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(r.err.find("cannot home X and Y without Z") != std::string::npos);
  CHECK(r.err.find("gc-relayer --resume-from-z <measured Z> " + reset_pieces() + " > resume.gcode") !=
        std::string::npos);
  auto log = gctest::read_reset_log(gctest::read_file(dir + "/executed.log"));
  REQUIRE(log.sessions.size() == 2);
  CHECK(log.sessions[1].empty());  // not a numbered line after the reset
}

TEST_CASE("gc-send --resume through a link drop: before it starts, while it asks the printer, in the way back",
          "[gc-send][reset][resume][reconnect]") {
  auto expected = gctest::commands_of(gctest::read_file(reset_pieces()));
  // Killed inside the way back after a reset (as above), then the link
  // drops for 0.25 s (5 simulated): just before the resumed session starts
  // (-1: the port is away for 2 s, which a loaded machine may take to start
  // gc-send); while gc-send asks the printer where it is: as soon as it has
  // the port open, 0.03 s after it took the journal's lock; once the
  // printer ran the handshake's M110 or 20 commands of the way back.
  // (Timed from gc-send's start alone, a loaded machine opened the port
  // after the drop had come and gone: CI counted 3 drops of 5.)
  int away = 0, while_asking = 0, in_handshake = 0, in_print = 0;
  for (const char* when : {"before the start", "once the port is open", "0.03 s after the lock", "after M110",
                           "20 commands into the way back"}) {
    INFO("link dropped " << when);
    const std::string what = when;
    std::string dir = gctest::temp_dir();
    const std::string journal = quote(dir + "/print.journal"), log = quote(dir + "/executed.log");
    // (The resumed gc-send writes its pid into the lock it takes.)
    const std::string locked = "rm -f " + journal + ".lock; (" + gctest::wait_until("[ -s " + journal + ".lock ]", 10000, 0.001);
    const std::string ran = "n=$(($(wc -l < " + log + ") + " + (what == "after M110" ? "1" : "20") + ")); (" +
                            gctest::wait_for_lines(log, {.at_least = "$((n + 1))", .tries = 10000, .every = 0.002});
    std::string drop = "sleep 0.5; ";
    if (what == "before the start") {
      drop += "kill -USR2 $vp; sleep 0.05";
    } else if (what == "once the port is open") {
      drop += "pts=$(readlink -f " + quote(dir + "/printer") + "); " + locked +
              gctest::wait_until("ls -l /proc/$(cat " + journal + ".lock)/fd 2>/dev/null | grep -q \"$pts\"", 10000, 0.001) +
              "kill -USR2 $vp) &";
    } else if (what == "0.03 s after the lock") {
      drop += locked + "sleep 0.03; kill -USR2 $vp) &";
    } else {
      drop += ran + "kill -USR2 $vp) &";
    }
    auto r = killed_when(dir, reset_pieces(), in_way_back(dir, 2), drop, "--reconnect 60",
                         std::string("--heat-rate 100 --fault reset@line=2500") +
                             (what == "before the start" ? " --drop-seconds 40" : ""));
    INFO(r.err);
    REQUIRE(r.status == 0);
    if (r.err.find("s for it (--reconnect)") != std::string::npos) ++away;
    if (r.err.find("the port is back after") != std::string::npos &&
        r.err.find("asking the printer again") != std::string::npos)
      ++while_asking;
    if (r.err.find("during the handshake (M110, M115); asking again") != std::string::npos) ++in_handshake;
    if (r.err.find("going on from N") != std::string::npos) ++in_print;
    CHECK(r.err.find("that way back again") != std::string::npos);
    CHECK(require_resumed(gctest::read_file(dir + "/executed.log"), expected).resets == 1);
  }
  // (Under load the drop 0.03 s after the lock may come before the port is
  // open, or while gc-send writes nothing: the link is back before it
  // notices.)
  CHECK(away >= 1);
  CHECK(while_asking >= 1);
  CHECK(in_print >= 1);
  CHECK(away + while_asking + in_handshake + in_print >= 4);
}
