// The sender's side of a printer reset (sender_reset.cpp) at the edges the
// fuzzer found: a line the reset cut off half written, and a line that no
// longer fits the firmware's buffer under the higher number its re-run gets.
#include <catch2/catch.hpp>

#include <string>

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
