// One gc-send per journal and per port: while a print runs with journal J,
// a second `gc-send --journal J` and a `gc-send --resume J` are refused,
// naming the holder's pid, exit 1, before they open the port; one with
// another journal or none is refused when it opens the port, before it sets
// or sends anything. The locks die with the holder: after a kill -9,
// `--resume J` takes them and finishes the print, and the printer's
// executed log holds every command of the input once, in order (nothing of
// the refused ones).
#include <catch2/catch.hpp>

#include <string>

#include "gcode/serial/journal/journal.hpp"
#include "pty_run.hpp"
#include "test_support.hpp"

using gctest::quote;
using gctest::tool_path;

TEST_CASE("gc-send: a second gc-send on a journal or a port in use, or a --resume, is refused, naming the holder, the "
          "locks end with a kill -9",
          "[gc-send][resume]") {
  const std::string& input = gctest::pieces_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 3000);
  std::string dir = gctest::temp_dir();
  std::string link = dir + "/printer";
  std::string journal = dir + "/print.journal";
  std::string second = dir + "/err-second", refused_resume = dir + "/err-resume";
  std::string no_journal = dir + "/err-no-journal", other_journal = dir + "/err-other-journal";
  std::string send = quote(tool_path("gc-send")) + " -q --port " + quote(link) + " ";
  auto refused = [&](const std::string& args, const std::string& err) {
    return send + args + " " + quote(input) + " 2> " + quote(err) + "; echo $? >> " + quote(err) + "\n";
  };
  std::string script =
      quote(tool_path("gc-virtual-printer")) + " -q --time-scale 20 --link " + quote(link) + " --log " +
      quote(dir + "/executed.log") + " & vp=$!\n" + gctest::wait_for_link(link) + send + "--journal " +
      quote(journal) + " " + quote(input) + " & gs=$!\n" + gctest::wait_until("[ -s " + quote(journal) + " ]", 500) +
      "sleep 0.3\n" +
      refused("--journal " + quote(journal), second) + refused("--resume " + quote(journal), refused_resume) +
      refused("--no-journal", no_journal) + refused("--journal " + quote(dir + "/other.journal"), other_journal) +
      "kill -0 $gs || echo ended-before-the-kill\n"
      "kill -9 $gs; wait $gs\n" +
      send + "--resume " + quote(journal) + " " + quote(input) + "; s=$?\n"
      "kill $vp; wait $vp; echo $gs; exit $s\n";
  gctest::PtyRun r;
  r.result = gctest::run(script);
  r.log_text = gctest::read_file(dir + "/executed.log");
  r.log = gctest::parse_executed_log(r.log_text);
  INFO(r.result.out << r.result.err);
  REQUIRE(r.result.out.find("ended-before-the-kill") == std::string::npos);  // the refusals came while it printed
  std::string pid = r.result.out.substr(0, r.result.out.find('\n'));
  for (const std::string& err : {gctest::read_file(second), gctest::read_file(refused_resume)}) {
    INFO(err);
    CHECK(err.find("the journal " + journal + " is in use by another gc-send (pid " + pid + ")") != std::string::npos);
    CHECK(err.substr(err.size() - 2) == "1\n");
  }
  for (const std::string& err : {gctest::read_file(no_journal), gctest::read_file(other_journal)}) {
    INFO(err);
    CHECK(err.find("the port " + link + " is in use by another gc-send (pid " + pid + ")") != std::string::npos);
    CHECK(err.substr(err.size() - 2) == "1\n");
  }
  gctest::require_exact(r, gctest::commands_of(gctest::read_file(input)));
  CHECK(gcode::serial::read_journal(journal).finished);
}
