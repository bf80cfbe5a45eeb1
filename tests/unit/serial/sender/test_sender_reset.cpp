// The sender's side of a printer reset (sender_reset.cpp) at the edges the
// fuzzer found: a line the reset cut off half written, and a line that no
// longer fits the firmware's buffer under the higher number its re-run gets.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "gcode/serial/protocol/line_check.hpp"
#include "gcode/serial/sender/sender.hpp"

using namespace gcode::serial;

namespace {

SenderConfig unhurried() {
  SenderConfig sc;
  sc.handshake = false;  // printing from the first line
  sc.flow = FlowMode::Window;
  sc.link_bytes_per_second = 0;
  return sc;
}

}  // namespace

TEST_CASE("sender: a reset while a line is half written ends the fragment with a newline before the handshake",
          "[serial][reset]") {
  Sender s(unhurried(), Sender::Logger());
  s.start(0);
  s.submit("G28", 1, 0);
  s.submit("G1 X10 Y10 F1200", 2, 0);
  s.pump(0);
  const std::string before(s.output());
  REQUIRE(before.rfind("N1 G28*", 0) == 0);
  // The port takes the first line and half of the second, then the board
  // restarts (nothing was extruded: the print starts again).
  const std::size_t cut = before.find('\n') + 5;
  s.written(cut, 0.01);
  s.on_line("start", 0.02);
  s.pump(0.02);
  const std::string after(s.output());
  INFO(after);
  CHECK(after.rfind("\nM110 N2\n", 0) == 0);
  CHECK(s.stats().resets == 1);
}

TEST_CASE("sender: a re-run line that no longer fits under its new number ends the print, saying which",
          "[serial][reset]") {
  SenderConfig sc = unhurried();
  sc.max_line = 40;
  // All nine go out before the reset (numbers that never went out are
  // given again, not moved up).
  sc.queue = 16;
  sc.rx_buffer = 1024;
  // A command that fits the buffer exactly as line 9 and, one digit more,
  // not as line 18, where the re-run after the reset puts it.
  std::string command = "G1 X1";
  while (check_line(command + "1", 9, sc.max_line).problem == LineProblem::None) command += "1";
  REQUIRE(check_line(command, 9, sc.max_line).problem == LineProblem::None);
  REQUIRE(check_line(command, 18, sc.max_line).problem != LineProblem::None);
  Sender s(sc, Sender::Logger());
  s.start(0);
  for (int i = 1; i <= 8; ++i) s.submit("G1 X" + std::to_string(i), static_cast<std::uint64_t>(i), 0);
  s.submit(command, 9, 0);
  s.pump(0);
  s.on_line("start", 0.01);
  CHECK(s.state() == SenderState::Failed);
  CHECK(s.failure().find("the printer reset, and input line 9 no longer fits under its new number") !=
        std::string::npos);
}

TEST_CASE("sender: after a reset the handshake names the last number that went out, and the way back's first line is journaled before it",
          "[serial][reset][journal]") {
  // Killed right after the handshake, gc-send --resume finds the printer at
  // the handshake's number: the journal must hold that number and, after
  // it, the way back (else it sees a number it never journaled and stops).
  SenderConfig sc = unhurried();
  sc.queue = 2;  // two lines in flight: the rest wait, numbered, unsent
  sc.planner_blocks = 2;  // the way back: two moves
  Sender s(sc, Sender::Logger());
  std::vector<NumberedCommand> journaled;
  std::size_t journaled_before_handshake = 0;
  s.set_journal_hooks([&](const NumberedCommand& c) { journaled.push_back(c); }, [](long long) {});
  s.start(0);
  s.submit("G28", 1, 0);
  s.submit("G1 Z0.2 F600", 2, 1);
  for (int i = 0; i < 20; ++i)
    s.submit("G1 X" + std::to_string(10 + i) + " Y10 E" + std::to_string(i + 1) + " F1200", static_cast<std::uint64_t>(3 + i), 1);
  s.pump(0);
  s.written(s.output().size(), 0);
  for (double t = 0.01; t < 0.085; t += 0.01) {  // the printer takes lines one by one
    s.on_line("ok", t);
    s.pump(t);
    s.written(s.output().size(), t);
  }
  const long long last_out = s.highest_sent();
  REQUIRE(last_out >= 5);
  REQUIRE(last_out < 22);  // some commands wait, numbered, unsent
  s.on_line("start", 0.1);
  journaled_before_handshake = journaled.size();
  s.pump(0.1);
  const std::string after(s.output());
  INFO(after);
  CHECK(after.find("M110 N" + std::to_string(last_out) + "\n") != std::string::npos);
  REQUIRE(journaled_before_handshake > 0);
  // The record written with the reset, before the handshake could go out.
  const NumberedCommand& way_back = journaled[journaled_before_handshake - 1];
  CHECK(way_back.n == last_out + 1);
  CHECK(way_back.restore > 0);
  long long highest = 0;
  for (std::size_t i = 0; i + 1 < journaled_before_handshake; ++i) highest = std::max(highest, journaled[i].n);
  CHECK(highest == last_out);  // every number the printer may hold is journaled
}
