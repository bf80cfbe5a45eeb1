// The soak (issue 22 §5): one long print through gc-virtual-printer with
// every fault a day of printing brings, at once: corrupted lines, lost oks,
// busy stalls, printer resets, link drops with the board running on and
// with it restarting, and gc-send itself killed with SIGKILL. A supervisor
// that knows nothing of the print (as a print farm's would) runs the
// command gc-send prints when a print stops with the part on the bed,
// until the print ends. The printer's executed log across all sessions
// holds every input command once, in order, but the re-run after each
// reset, which stays within what the printer buffers.
//
// GC_SOAK_LINES sets the length (lines of the Prusa cube in 0.2 mm pieces,
// default 9000; 0: the whole file, about 45 minutes of printing, a few
// minutes here at time scale 200).
#include <catch2/catch.hpp>

#include <cstdlib>
#include <random>
#include <string>

#include "pty_run.hpp"
#include "reset_check.hpp"
#include "test_support.hpp"

using gctest::quote;
using gctest::tool_path;

namespace {

int soak_lines() {
  const char* v = std::getenv("GC_SOAK_LINES");
  return v != nullptr ? std::atoi(v) : 9000;
}

// Faults at seeded moments spread over the print, `every` commands apart:
// resets, drops (the board runs on) and drops that end in a restart, in turn.
std::string scheduled_faults(std::size_t commands, std::mt19937& rng) {
  std::string faults = "corrupt=0.002 drop-ok=0.001 busy=0.002 seed=" + std::to_string(rng() % 1000);
  const std::size_t every = 2500;
  std::uniform_int_distribution<std::size_t> jitter(0, every / 2);
  const char* kinds[] = {"reset@line=", "drop=2@line=", "drop-reset=2@line="};
  int k = 0;
  for (std::size_t at = every; at + 200 < commands; at += every, ++k)
    faults += std::string(" ") + kinds[k % 3] + std::to_string(at + jitter(rng));
  return faults;
}

// The supervisor: gc-send with a journal, killed with SIGKILL `kills` times
// at `kill_after` seconds into a session (counted from the journal's first
// acknowledgement: a loaded machine can take a second to start gc-send, and
// a print killed before its first command only begins again, which a
// resume test of its own covers); whenever it stops with status 1
// and prints the command that resumes the print, that command runs next.
std::string supervisor(const std::string& dir, const std::string& input, const std::string& faults, int kills,
                       double kill_after) {
  const std::string port = dir + "/printer", journal = dir + "/print.journal", err = dir + "/stderr";
  const std::string send = quote(tool_path("gc-send")) + " --port " + quote(port) + " --journal " + quote(journal) +
                           " --reconnect 60";
  return quote(tool_path("gc-virtual-printer")) + " -q --time-scale 200 --heat-rate 1000 --link " + quote(port) +
         " --log " + quote(dir + "/executed.log") + " --fault " + faults + " & vp=$!\n" +
         gctest::wait_for_link(port) +
         "cmd=" + quote(send + " " + quote(input)) + "\nkills=" + std::to_string(kills) + "\n" +
         "for session in $(seq 30); do\n"
         // exec: $gs is gc-send itself, not a subshell around it.
         "  eval \"exec $cmd\" 2>" + quote(err) + ".$session & gs=$!\n"
         "  if [ $kills -gt 0 ]; then\n"
         "    (" + gctest::wait_for_journal_start(journal) + "sleep " +
         std::to_string(kill_after) + "; kill -9 $gs 2>/dev/null) & killer=$!\n"
         "  fi\n"
         "  wait $gs; s=$?\n"
         "  [ $kills -gt 0 ] && { kill $killer 2>/dev/null; wait $killer 2>/dev/null; }\n"
         "  cat " + quote(err) + ".$session >&2\n"
         "  [ $s -eq 0 ] && break\n"
         "  if [ $s -eq 137 ]; then kills=$((kills - 1)); cmd=" + quote(send + " --resume " + quote(journal) + " " +
                                                                       quote(input)) + "; continue; fi\n"
         // Not killed: gc-send gave up on the print and says how to resume it.
         "  next=$(grep -o 'gc-send --resume.*' " + quote(err) + ".$session | tail -n 1)\n"
         "  [ -n \"$next\" ] || break\n"
         "  cmd=" + quote(send + " --resume " + quote(journal) + " " + quote(input)) + "\n"
         "done\n"
         "kill $vp; wait $vp; exit $s";
}

}  // namespace

TEST_CASE("gc-send soak: resets, link drops, lost oks, corrupted lines and kill -9 in one print: every command once",
          "[gc-send][reset][resume][soak]") {
  const int lines = soak_lines();
  const std::string& input = gctest::pieces_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", lines > 0 ? lines : 10000000);
  auto expected = gctest::commands_of(gctest::read_file(input));
  std::mt19937 rng(22);
  const std::string faults = scheduled_faults(expected.size(), rng);
  const std::string dir = gctest::temp_dir();
  gctest::RunResult r = gctest::run(supervisor(dir, input, faults, 2, 0.8));
  INFO(faults << "\n" << r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find("resuming: ") != std::string::npos);       // after the kills
  CHECK(r.err.find("the printer reset") != std::string::npos);
  CHECK(r.err.find("reconnect") != std::string::npos);
  const gctest::ResetFigures f = gctest::require_resumed(gctest::read_file(dir + "/executed.log"), expected);
  CHECK(f.resets >= 2);  // the resets and the drops that restart
}
