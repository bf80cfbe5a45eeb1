// gc-send --resume after gc-send was killed (SIGKILL) while gc-virtual-printer
// went on printing on its pty: the printer's executed log, across both
// sessions, holds every command of the input once and in order (a file, the
// journal and the file found by default, and a pipeline re-run the same
// way, and killed again and again at seeded random moments); killed inside
// gc-send's closing M400, the print is found complete, and inside a cancel's
// end, never resumed; and every bad start is refused with its reason, exit
// 1, before any line of the print is sent.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <random>
#include <string>

#include "gcode/serial/journal/journal.hpp"
#include "control_run.hpp"
#include "reset_check.hpp"
#include "serial_check.hpp"
#include "test_support.hpp"

using gctest::quote;
using gctest::run;
using gctest::tool_path;

namespace {

// 3000 commands of a real print in pieces of at most 0.5 mm.
std::string subdivided_part(const std::string& dir) {
  std::string path = dir + "/part.gcode";
  auto r = run(quote(tool_path("gc-subdivide")) + " --max 0.5 " +
               quote(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")) + " | head -n 3000 > " + quote(path));
  REQUIRE(r.status == 0);
  return path;
}

// A shell script's start: the printer on a pty at `dir`/printer, its log
// `dir`/executed.log; `$vp` its process.
std::string printer_up(const std::string& dir) {
  std::string link = dir + "/printer";
  return quote(tool_path("gc-virtual-printer")) + " -q --time-scale 20 --link " + quote(link) + " --log " +
         quote(dir + "/executed.log") + " & vp=$!\n" + gctest::wait_for_link(link);
}

std::string gc_send(const std::string& args) { return quote(tool_path("gc-send")) + " " + args; }

// `command` (gc-send, or a pipeline that ends in it) started and gc-send
// killed with SIGKILL once the printer on `dir`/printer has run `commands`
// more numbered commands (a count, not a time: a loaded machine runs
// everything later, gc-send's start too).
std::string killed_after(const std::string& command, const std::string& dir, int commands) {
  return "n0=$(" + gctest::numbered_log_count(dir + "/executed.log") + ")\n" + command + " 2>/dev/null & gs=$!\n" +
         gctest::wait_for_lines(quote(dir + "/executed.log"), {.match = gctest::numbered_log_line(),
                                                               .at_least = "$((n0 + " + std::to_string(commands) + "))",
                                                               .while_alive = "$gs", .tries = 6000}) +
         "kill -9 $gs; wait $gs 2>/dev/null\n";
}

// A shell snippet that waits until the printer on `dir`/printer has run
// what it took: its log still for 1.5 s (once, a fixed sleep of 2 s was too
// short on a loaded machine: the count grew after it, with nothing sent).
std::string printer_still(const std::string& dir) {
  return "p=-1; for i in $(seq 100); do c=$(wc -l < " + quote(dir + "/executed.log") +
         "); [ \"$c\" = \"$p\" ] && break; p=$c; sleep 1.5; done\n";
}

// A shell command that counts the numbered lines the printer executed
// (M114 and the like are not).
std::string numbered_count(const std::string& dir) { return gctest::numbered_log_count(dir + "/executed.log"); }

void require_every_command_once(const std::string& dir, const std::string& input) {
  auto executed = gctest::parse_executed_log(gctest::read_file(dir + "/executed.log"));
  auto expected = gctest::commands_of(gctest::read_file(input));
  gctest::drop_own_lines(executed, expected);
  REQUIRE(executed.commands.size() == expected.size() + 1);  // and the resumed run's M400
  for (std::size_t i = 0; i < expected.size(); ++i) {
    INFO("command " << i);
    REQUIRE(executed.commands[i] == expected[i].text);
  }
  CHECK(gctest::numbers_rise(executed.numbers));
  CHECK(executed.commands.back() == "M400");
}

}  // namespace

TEST_CASE("gc-send --resume after kill -9: every command of the file once, in order", "[gc-send][resume]") {
  std::string dir = gctest::temp_dir();
  std::string input = subdivided_part(dir);
  std::string port = dir + "/printer";
  std::string journal = dir + "/print.journal";
  std::string script = printer_up(dir) +
                       killed_after(gc_send("-q --port " + quote(port) + " --journal " + quote(journal) + " " + quote(input)), dir, 1000) +
                       gc_send("--port " + quote(port) + " --resume " + quote(journal) + " " + quote(input)) +
                       "; s=$?; kill $vp; wait $vp; exit $s";
  auto r = run(script);
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find("resuming: the printer kept running and took line ") != std::string::npos);
  require_every_command_once(dir, input);
}

TEST_CASE("gc-send --resume of a print killed before its first command begins it: every command once",
          "[gc-send][resume]") {
  // A supervisor resumes whatever was killed, also in gc-send's first
  // second: the printer was stopped (SIGSTOP), so gc-send waited for its
  // answer to M110 with no command journaled when the kill came.
  std::string dir = gctest::temp_dir();
  std::string input = subdivided_part(dir);
  std::string port = dir + "/printer";
  std::string journal = dir + "/print.journal";
  std::string script = printer_up(dir) + "kill -STOP $vp\n" +
                       gc_send("-q --port " + quote(port) + " --journal " + quote(journal) + " " + quote(input)) +
                       " 2>/dev/null & gs=$!\n" +
                       gctest::wait_for_lines(quote(journal), {.match = "'^H '", .tries = 5000, .every = 0.002}) +
                       "kill -9 $gs; wait $gs 2>/dev/null; kill -CONT $vp\n" +
                       "grep -c '^[SD] ' " + quote(journal) + " >&2\n" +
                       gc_send("--port " + quote(port) + " --resume " + quote(journal)) +
                       "; s=$?; kill $vp; wait $vp; exit $s";
  auto r = run(script);
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.rfind("0\n", 0) == 0);  // the killed run had journaled no command
  CHECK(r.err.find("holds no command: the print had not begun; beginning it") != std::string::npos);
  CHECK(gcode::serial::read_journal(journal).finished);
  require_every_command_once(dir, input);
}

TEST_CASE("gc-send --resume with the default journal and the journal's file, and a pipeline re-run",
          "[gc-send][resume]") {
  std::string dir = gctest::temp_dir();
  std::string input = subdivided_part(dir);
  std::string port = dir + "/printer";
  std::string env = "XDG_STATE_HOME=" + quote(dir + "/state") + " ";
  SECTION("a file: --resume alone finds the port's journal and the file it names") {
    std::string script = printer_up(dir) + "cd /\n" +
                         killed_after(env + gc_send("-q --port " + quote(port) + " " + quote(input)), dir, 1000) + env +
                         gc_send("--port " + quote(port) + " --resume") + "; s=$?; kill $vp; wait $vp; exit $s";
    auto r = run(script);
    INFO(r.err);
    REQUIRE(r.status == 0);
    require_every_command_once(dir, input);
  }
  SECTION("a pipeline: its bytes up to the resume hash as before") {
    std::string cat = "cat " + quote(input) + " | ";
    std::string script = printer_up(dir) + killed_after(cat + env + gc_send("-q --port " + quote(port)), dir, 1000) + cat + env +
                         gc_send("--port " + quote(port) + " --resume -") + "; s=$?; kill $vp; wait $vp; exit $s";
    auto r = run(script);
    INFO(r.err);
    REQUIRE(r.status == 0);
    require_every_command_once(dir, input);
  }
}

TEST_CASE("gc-send --resume refuses, exit 1, nothing sent: another file, a corrupt, finished or missing journal, "
          "an open folder, a printer that moved",
          "[gc-send][resume]") {
  std::string dir = gctest::temp_dir();
  std::string input = subdivided_part(dir);
  std::string other = dir + "/other.gcode";
  gctest::write_file(other, gctest::read_file(input) + "G1 X1\n");
  std::string port = dir + "/printer";
  std::string journal = dir + "/print.journal";
  std::string open_dir = dir + "/open";
  REQUIRE(::mkdir(open_dir.c_str(), 0777) == 0);
  REQUIRE(::chmod(open_dir.c_str(), 0777) == 0);
  // A finished journal: a whole print on the built-in printer.
  REQUIRE(run(gc_send("-q --port virtual:time-scale=100 --journal " + quote(dir + "/done.journal")),
              "G28\nG1 X5 F6000\n").status == 0);
  std::string numbered = numbered_count(dir);
  auto resume = [&](const std::string& name, const std::string& args) {
    return gc_send("-q --port " + quote(port) + " --resume " + args) + " 2> " + quote(dir + "/err-" + name) + "; echo $? >> " +
           quote(dir + "/err-" + name) + "\n";
  };
  std::string script =
      printer_up(dir) + killed_after(gc_send("-q --port " + quote(port) + " --journal " + quote(journal) + " " + quote(input)), dir, 1000) +
      printer_still(dir) + "n=$(" + numbered + ")\n"
      "sed '5s/ n=/ n=9/' " + quote(journal) + " > " + quote(dir + "/corrupt.journal") + "\n"
      "cp " + quote(journal) + " " + quote(open_dir + "/open.journal") + "\n" +
      resume("other", quote(journal) + " " + quote(other)) +
      resume("corrupt", quote(dir + "/corrupt.journal") + " " + quote(input)) +
      resume("finished", quote(dir + "/done.journal") + " " + quote(input)) +
      resume("missing", quote(dir + "/none.journal") + " " + quote(input)) +
      resume("open", quote(open_dir + "/open.journal") + " " + quote(input)) +
      "[ $(" + numbered + ") = $n ] || echo sent-something\n"
      // Someone moved the printer meanwhile (an unnumbered line on its pty).
      "printf 'G91\\nG1 Z0.5 F600\\nG90\\n' > " + quote(port) + "\n" +
      gctest::wait_for_lines(quote(dir + "/executed.log"), {.match = "'	G90$'", .after = "'	G1 Z0.5 F600$'"}) +
      "n=$(" + numbered + ")\n" +
      resume("moved", quote(journal) + " " + quote(input)) +
      "[ $(" + numbered + ") = $n ] || echo sent-something\n"
      "kill $vp; wait $vp\n";
  auto r = run(script);
  INFO(r.out << r.err);
  CHECK(r.out.find("sent-something") == std::string::npos);
  auto refused = [&](const std::string& name, const std::string& message) {
    std::string err = gctest::read_file(dir + "/err-" + name);
    INFO(name << ": " << err);
    CHECK(err.find(message) != std::string::npos);
    CHECK(err.substr(err.size() - 2) == "1\n");
  };
  refused("other", "cannot resume: the journal is of " + input + ", not " + other);
  refused("corrupt", "is corrupt: line 5 is damaged and good records follow it");
  refused("finished", "ended normally (nothing to resume)");
  refused("missing", "no journal at " + dir + "/none.journal");
  refused("open", "journal refused: its folder " + open_dir + " can be changed by others");
  refused("moved", "the printer is at Z ");
  // Usage: the built-in virtual printer ended with the gc-send that ran it.
  auto u = run(gc_send("--port virtual --resume " + quote(journal)));
  CHECK(u.status == 2);
  CHECK(u.err.find("--resume needs the port of the printer") != std::string::npos);
}

TEST_CASE("gc-send killed with SIGKILL at random moments, resumed each time: the journal reads back every time and "
          "the printer ran every command once, in order",
          "[gc-send][resume]") {
  std::string dir = gctest::temp_dir();
  std::string input = subdivided_part(dir);
  std::string port = dir + "/printer";
  std::string journal = dir + "/print.journal";
  std::string pid_file = dir + "/printer.pid";
  std::string link = quote(port);
  REQUIRE(run(quote(tool_path("gc-virtual-printer")) + " -q --time-scale 20 --link " + link + " --log " +
              quote(dir + "/executed.log") + " >/dev/null 2>&1 & echo $! > " + quote(pid_file) +
              "\n" + gctest::wait_for_link(port))
              .status == 0);
  std::mt19937 rng(22);  // seeded: the same moments on every run
  std::uniform_int_distribution<int> moment(20, 1500);  // commands the printer runs before the kill
  std::string first = "-q --port " + link + " --journal " + quote(journal) + " " + quote(input);
  std::string again = "-q --port " + link + " --resume " + quote(journal) + " " + quote(input);
  bool finished = false;
  for (int kill = 0; kill < 4 && !finished; ++kill) {
    int at = moment(rng);
    INFO("kill " << kill << " after " << at << " commands");
    run(killed_after(gc_send(kill == 0 ? first : again), dir, at));
    gcode::serial::JournalContents c;
    REQUIRE_NOTHROW(c = gcode::serial::read_journal(journal));
    REQUIRE_FALSE(c.entries.empty());
    finished = c.finished;  // that run got to the end first
  }
  if (!finished) {
    auto r = run(gc_send(again));
    INFO(r.err);
    REQUIRE(r.status == 0);
  }
  run("kill $(cat " + quote(pid_file) + ")");
  CHECK(gcode::serial::read_journal(journal).finished);
  require_every_command_once(dir, input);
}

TEST_CASE("gc-send --resume after a kill -9 inside gc-send's closing M400: the print is complete, nothing sent, the "
          "journal marked finished",
          "[gc-send][resume]") {
  std::string dir = gctest::temp_dir();
  // The start of a real print and its end code's moves, the last a 48 mm
  // lift at 12 mm/s that keeps the closing M400 unanswered for a while:
  // the kill comes while it waits.
  std::string input = dir + "/part.gcode";
  std::string fixture = quote(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode"));
  REQUIRE(run(quote(tool_path("gc-subdivide")) + " --max 0.5 " + fixture + " | head -n 1500 > " + quote(input) +
              "; grep -v '^;' " + fixture + " | grep -B5 '^G1 Z69' >> " + quote(input))
              .status == 0);
  std::string port = dir + "/printer";
  std::string journal = dir + "/print.journal";
  std::string numbered = numbered_count(dir);
  std::string script =
      printer_up(dir) + gc_send("-q --port " + quote(port) + " --journal " + quote(journal) + " " + quote(input)) +
      " 2>/dev/null & gs=$!\n" + gctest::wait_for_lines(quote(journal), {.match = "' own=1 '", .tries = 3000, .every = 0.005}) +
      "kill -9 $gs; wait $gs 2>/dev/null\n"
      "grep -q '^F ' " + quote(journal) + " && echo finished-before-the-kill\n" +
      printer_still(dir) + "n=$(" + numbered + ")\n" +
      gc_send("--port " + quote(port) + " --resume " + quote(journal) + " " + quote(input)) + "; s=$?\n"
      "[ $(" + numbered + ") = $n ] || echo sent-something\n" +
      gc_send("-q --port " + quote(port) + " --resume " + quote(journal) + " " + quote(input)) +
      " 2>/dev/null || echo refused-as-finished\n"
      "kill $vp; wait $vp; exit $s";
  auto r = run(script);
  INFO(r.out << r.err);
  REQUIRE(r.out.find("finished-before-the-kill") == std::string::npos);  // the kill came inside the closing block
  REQUIRE(r.status == 0);
  CHECK(r.err.find("the print is complete: the printer had taken every line of the input and gc-send's closing M400") !=
        std::string::npos);
  CHECK(r.out.find("sent-something") == std::string::npos);
  CHECK(r.out.find("refused-as-finished") != std::string::npos);
  CHECK(gcode::serial::read_journal(journal).finished);
  require_every_command_once(dir, input);  // the M400 the first session sent is the one at the end
}

TEST_CASE("gc-send --resume inside a layer: the resumed session is in that layer until the next, in its progress, its "
          "journal and a reset's warning",
          "[gc-send][resume][reset]") {
  std::string dir = gctest::temp_dir();
  std::string input = subdivided_part(dir);
  std::string port = dir + "/printer";
  std::string journal = dir + "/print.journal";
  // Killed once the printer has executed 440 numbered lines (layer 1 starts
  // at about the 240th command and ends before the 340th, and gc-send's own numbered probes and polls
  // are among them: a count, not a time, so a loaded machine kills it at the
  // same place); the printer resets 20 lines into the resumed session,
  // before the file's next layer marker.
  std::string script =
      printer_up(dir) + gc_send("-q --port " + quote(port) + " --journal " + quote(journal) + " " + quote(input)) +
      " 2>/dev/null & gs=$!\n" +
      gctest::wait_for_lines(quote(dir + "/executed.log"), {.match = gctest::numbered_log_line(), .at_least = "440",
                                                           .while_alive = "$gs", .tries = 60000, .every = 0.005}) +
      "kill -9 $gs; wait $gs 2>/dev/null\n"
      "n0=$(" + numbered_count(dir) + ")\n(" +
      gctest::wait_for_lines(quote(dir + "/executed.log"),
                             {.match = gctest::numbered_log_line(), .at_least = "$((n0 + 20))", .tries = 60000, .every = 0.005}) +
      "kill -USR1 $vp) &\n" +
      gc_send("--port " + quote(port) + " --resume " + quote(journal) + " " + quote(input)) +
      "; s=$?; kill $vp; wait $vp; exit $s";
  auto r = run(script);
  INFO(r.err);
  REQUIRE(r.status == 0);
  // "took line 1234 last (input line 1300, layer 1)"
  const std::string took = "resuming: the printer kept running and took line ";
  std::size_t at = r.err.find(", layer ", r.err.find(took));
  REQUIRE(at != std::string::npos);
  int layer = std::stoi(r.err.substr(at + 8));
  auto taken = static_cast<std::uint64_t>(gctest::number_after(r.err, took));
  REQUIRE(layer >= 1);  // killed inside the print, not in its start code
  CHECK(r.err.find("start code") == std::string::npos);  // the progress lines included
  CHECK(r.err.find("printing   layer " + std::to_string(layer)) != std::string::npos);
  std::size_t warning = r.err.find("the printer reset (");
  REQUIRE(warning != std::string::npos);
  std::string said = r.err.substr(warning, r.err.find('\n', warning) - warning);
  INFO(said);
  CHECK(said.find("start code") == std::string::npos);
  CHECK(said.find("(layer " + std::to_string(layer) + ")") != std::string::npos);
  // Every command the resumed session journalled is of that layer or later.
  // (The journal also carries the first session's last commands, up to the
  // one the printer took last: those may be of the start code.)
  gcode::serial::JournalContents c = gcode::serial::read_journal(journal);
  CHECK(c.finished);
  std::size_t resumed = 0;
  for (const gcode::serial::JournalEntry& e : c.entries) {
    if (e.n <= taken) continue;
    ++resumed;
    INFO("line " << e.n << ": " << e.point.get("line") << ", layer " << e.point.get("layer"));
    CHECK(e.point.count("layer") >= static_cast<std::uint64_t>(layer));
  }
  CHECK(resumed > 1000);
  CHECK(gctest::require_resumed(gctest::read_file(dir + "/executed.log"),
                                gctest::commands_of(gctest::read_file(input)))
            .resets == 1);
}

TEST_CASE("gc-send --resume after a kill -9 while a cancel's end went out: never resumed, the print ended or refused "
          "while its heaters may be on",
          "[gc-send][resume]") {
  for (bool reset : {false, true}) {
    INFO((reset ? "the printer reset since" : "the printer ran on"));
    std::string dir = gctest::temp_dir();
    std::string input = subdivided_part(dir);
    std::string port = dir + "/printer", journal = dir + "/print.journal", fifo = dir + "/control";
    std::string numbered = numbered_count(dir);
    std::string script =
        // A slow lift (10 mm at 0.5 mm/s): the cancel's end lasts a second, so the kill
        // lands inside it however late a loaded machine runs the script.
        printer_up(dir) + gc_send("-q --lift 10 --z-speed 0.5 --port " + quote(port) + " --journal " + quote(journal) +
                                  " --control " + quote(fifo) + " " + quote(input)) +
        " 2>/dev/null & gs=$!\n" +
        // Inside layer 1: 100 of its commands done.
        gctest::wait_for_lines(quote(journal), {.match = "'^D '", .after = "' layer=1 '", .at_least = "100"}) +
        "echo cancel > " + quote(fifo) + "\n" +
        gctest::wait_for_lines(quote(journal), {.match = "' state=cancelling '", .tries = 2000, .every = 0.002}) +
        "kill -9 $gs; wait $gs 2>/dev/null\n"
        "grep -q '^F ' " + quote(journal) + " && echo finished-before-the-kill\n" +
        (reset ? "kill -USR1 $vp\n" : "") +
        printer_still(dir) + "cp " + quote(journal) + " " + quote(dir + "/before.journal") +
        "\nn=$(" + numbered + ")\n" +
        gc_send("--port " + quote(port) + " --resume " + quote(journal) + " " + quote(input)) + "; s=$?\n"
        "[ $(" + numbered + ") = $n ] || echo sent-something\n"
        "kill $vp; wait $vp; exit $s";
    auto r = run(script);
    INFO(r.out << r.err);
    REQUIRE(r.out.find("finished-before-the-kill") == std::string::npos);
    CHECK(r.out.find("sent-something") == std::string::npos);
    // Whether the printer took the whole of the cancel's end: the newest
    // numbered line it ran against the journal's newest.
    auto ran = gctest::parse_executed_log(gctest::read_file(dir + "/executed.log"));
    REQUIRE_FALSE(ran.numbers.empty());
    const bool whole = ran.numbers.back() ==
                       static_cast<long long>(gcode::serial::read_journal(dir + "/before.journal").entries.back().n);
    if (reset) {
      CHECK(r.status == 0);
      CHECK(r.err.find("the print was being cancelled when gc-send stopped, and the printer reset since") !=
            std::string::npos);
    } else if (whole) {
      CHECK(r.status == 0);
      CHECK(r.err.find("the print was cancelled: the printer had taken the whole of the cancel's end") !=
            std::string::npos);
    } else {
      CHECK(r.status == 1);
      CHECK(r.err.find("its heaters may still be on") != std::string::npos);
    }
    CHECK(gcode::serial::read_journal(journal).finished == (r.status == 0));
  }
}
