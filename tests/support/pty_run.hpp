#pragma once
// Shared by the gc-send tool tests: gc-virtual-printer on a pseudo-terminal,
// gc-send against it, and what the printer's log says it executed.
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <vector>

#include "serial_check.hpp"
#include "test_support.hpp"

namespace gctest {

// A virtual printer 200 times real time that heats at once, for the
// gc-send tests of faults.
inline const std::string kFastPrinter = "--time-scale 200 --heat-rate 1000 ";

// The first `lines` lines of a fixture cut into 0.2 mm pieces (as
// gc-subdivide --max 0.2 makes them), made once per test run.
inline const std::string& pieces_of(const std::string& fixture, int lines) {
  static std::map<std::string, std::string> made;
  std::string& path = made[fixture + ":" + std::to_string(lines)];
  if (path.empty()) {
    std::string p = temp_dir() + "/pieces.gcode";
    auto r = run(quote(tool_path("gc-subdivide")) + " --max 0.2 " + quote(fixture_path(fixture)) + " | head -n " +
                 std::to_string(lines) + " > " + quote(p));
    REQUIRE(r.status == 0);
    path = p;
  }
  return path;
}

struct PtyRun {
  RunResult result;
  ExecutedLog log;
  std::string log_text;
};

// Starts gc-virtual-printer on a pty, runs gc-send against it, stops the
// printer. With `during`, gc-send runs in the background while that shell
// script runs ($gs is its pid), and its status is awaited after it.
inline PtyRun send_through_pty(const std::string& file, const std::string& send_args, const std::string& printer_args,
                               const std::string& during = "") {
  std::string dir = temp_dir();
  std::string link = dir + "/printer";
  std::string log = dir + "/executed.log";
  std::string send = quote(tool_path("gc-send")) + " --port " + quote(link) + " " + send_args + " " + quote(file);
  std::string script = quote(tool_path("gc-virtual-printer")) + " -q --link " + quote(link) + " --log " + quote(log) +
                       " " + printer_args + " & vp=$!\n" +
                       wait_for_link(link) +
                       (during.empty() ? send + "; status=$?\n" : send + " & gs=$!\n" + during + "\nwait $gs; status=$?\n") +
                       "kill $vp; wait $vp; exit $status";
  PtyRun r;
  r.result = run(script);
  r.log_text = read_file(log);
  r.log = parse_executed_log(r.log_text);
  return r;
}

// The printer executed exactly the input's commands, numbered as sent, in
// order, then the final M400; across all the sessions its log covers.
// (gc-send's own M105s and pace probes, numbered among them, left out.)
inline void require_exact(const PtyRun& r, const std::vector<SentCommand>& expected) {
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  ExecutedLog log = r.log;
  drop_own_lines(log, expected);
  REQUIRE(log.commands.size() == expected.size() + 1);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    INFO("command " << i);
    REQUIRE(log.commands[i] == expected[i].text);
  }
  CHECK(numbers_rise(log.numbers));
  CHECK(log.commands.back() == "M400");
}

}  // namespace gctest
