// gc-send --reconnect against gc-virtual-printer's link drops (its pty goes
// away and comes back at the same path): a printer that ran on gets the rest
// of the print, every move once and in order, across both sessions; a port
// that stays away longer than --reconnect stops the print with a message
// that says what happened (one that restarted comes back:
// test_gc_send_reset.cpp). While gc-send waits, its
// status file says "reconnecting" and a cancel ends the wait.
#include <catch2/catch.hpp>

#include <string>

#include "pty_run.hpp"
#include "serial_check.hpp"
#include "test_support.hpp"

using gctest::PtyRun;
using gctest::quote;
using gctest::require_exact;
using gctest::send_through_pty;

namespace {

// The first 6000 lines of a real slicer file cut into 0.2 mm pieces.
const std::string& drop_pieces() { return gctest::pieces_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 6000); }

}  // namespace

TEST_CASE("gc-send: a link drop in the start code or mid-layer while the printer runs on: the print completes, every move once, in order",
          "[gc-send][reconnect]") {
  auto expected = gctest::commands_of(gctest::read_file(drop_pieces()));
  REQUIRE(expected.size() > 5000);
  // In the start code and mid-layer; 100 simulated seconds are half a
  // second of wall time without a port.
  for (const char* fault : {"drop=20@line=4", "drop=100@line=3000"}) {
    PtyRun r = send_through_pty(drop_pieces(), "--reconnect 30", gctest::kFastPrinter + "--fault " + fault);
    INFO(fault << ": " << r.result.err);
    // One log over both sessions.
    require_exact(r, expected);
    CHECK(r.result.err.find("lost the printer's port") != std::string::npos);
    CHECK(r.result.err.find("the port is back after") != std::string::npos);
    CHECK(r.result.err.find("the printer ran on and stands where N") != std::string::npos);
    REQUIRE(r.log.notes.size() == 2);
    CHECK(r.log.notes[0].rfind("# link down at ", 0) == 0);
    CHECK(r.log.notes[1].rfind("# link up at ", 0) == 0);
  }
}

TEST_CASE("gc-send: a port that stays away longer than --reconnect stops the print cleanly, saying so",
          "[gc-send][reconnect]") {
  auto expected = gctest::commands_of(gctest::read_file(drop_pieces()));
  // 2000 simulated seconds are 10 s of wall time; gc-send waits 1 s.
  // (--no-pace: no pace probes among the numbers, so line 1000 is the input's.)
  PtyRun r = send_through_pty(drop_pieces(), "--reconnect 1 --no-pace", gctest::kFastPrinter + "--fault drop=2000@line=1000");
  INFO(r.result.err);
  CHECK(r.result.status == 1);
  CHECK(r.result.err.find("did not come back within 1 s (--reconnect)") != std::string::npos);
  CHECK(r.result.err.find("last acknowledged: line ") != std::string::npos);
  // What ran is the start of the input, in order, nothing twice.
  gctest::drop_own_lines(r.log, expected);
  REQUIRE(r.log.commands.size() >= 1000);
  REQUIRE(r.log.commands.size() < expected.size());
  for (std::size_t i = 0; i < r.log.commands.size(); ++i) {
    INFO("command " << i);
    REQUIRE(r.log.commands[i] == expected[i].text);
  }
}

TEST_CASE("gc-send: while it waits for the port the status file says reconnecting, and a cancel ends the wait",
          "[gc-send][reconnect]") {
  std::string dir = gctest::temp_dir();
  std::string status = dir + "/status.json";
  std::string fifo = dir + "/control";
  // The drop lasts 60 s of wall time; the cancel comes as soon as the
  // status file says reconnecting.
  std::string during = gctest::wait_for_lines(quote(status), {.match = quote("\"reconnecting\""), .tries = 600, .every = 0.02}) +
                       "grep -o '\"state\": *\"[a-z]*\"' " + quote(status) + " >&2\n"
                       "echo status > " + quote(fifo) + "; sleep 0.3; echo cancel > " + quote(fifo);
  PtyRun r = send_through_pty(drop_pieces(),
                              "--reconnect 120 --status-file " + quote(status) + " --control " + quote(fifo),
                              gctest::kFastPrinter + "--fault drop=12000@line=1000", during);
  INFO(r.result.err);
  CHECK(r.result.status == 1);
  CHECK(r.result.err.find("\"reconnecting\"") != std::string::npos);  // the status file
  CHECK(r.result.err.find("gc-send: reconnecting") != std::string::npos);  // the FIFO's status answer
  CHECK(r.result.err.find("cancelled while waiting for the port to come back") != std::string::npos);
}
