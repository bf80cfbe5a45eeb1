// The Marlin model behind gc-send --port virtual and gc-virtual-printer
// (gcode/serial/sim/virtual_printer.hpp): link timing, the RX buffer, Marlin's
// error replies, and answers only when a command leaves the queue.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "gcode/serial/protocol/protocol.hpp"
#include "gcode/serial/sim/virtual_printer.hpp"
#include "printer_talk.hpp"

using namespace gcode::serial;
using gctest::answers;
using gctest::numbered;

TEST_CASE("virtual printer: greets, and bytes take one byte time each way", "[serial]") {
  VirtualPrinterConfig c;
  c.baud = 250000;  // 40 us per byte
  VirtualPrinter p(c);
  CHECK(answers(p, 1) == std::vector<std::string>{"start"});
  p.receive("G90\n", 1.0);  // 4 bytes arrive by 1.00016, "ok\n" is sent by 1.00028
  CHECK(answers(p, 1.000279).empty());
  CHECK(answers(p, 1.000281) == std::vector<std::string>{"ok"});
}

TEST_CASE("virtual printer: Marlin's line number and checksum errors, then Resend and ok", "[serial]") {
  VirtualPrinter p(VirtualPrinterConfig{});
  answers(p, 1);
  p.receive("M110 N0\n" + numbered(1, "G90") + numbered(3, "G91"), 1);
  CHECK(answers(p, 2) == std::vector<std::string>{"ok", "ok", "Error:Line Number is not Last Line Number+1, Last Line: 1",
                                                  "Resend: 2", "ok"});
  p.receive("N2 G90*99\n", 2);
  CHECK(answers(p, 3) == std::vector<std::string>{"Error:checksum mismatch, Last Line: 1", "Resend: 2", "ok"});
  p.receive("N2 G90\n", 3);
  CHECK(answers(p, 4) == std::vector<std::string>{"Error:No Checksum with line number, Last Line: 1", "Resend: 2", "ok"});
  p.receive(numbered(2, "G90"), 4);
  CHECK(answers(p, 5) == std::vector<std::string>{"ok"});
  CHECK(p.stats().accepted_lines == 2);
}

TEST_CASE("virtual printer: the ok comes when the command leaves the queue", "[serial]") {
  VirtualPrinterConfig c;
  c.advanced_ok = true;
  VirtualPrinter p(c);
  answers(p, 1);
  // G4 waits 2 s; the G1 behind it waits in the RX buffer: Marlin reads no
  // new lines while a command blocks.
  p.receive("G4 P2000\nG1 X10 F600\n", 1);
  CHECK(answers(p, 2.5).empty());
  std::vector<std::string> later = answers(p, 3.1);
  REQUIRE(later.size() == 3);
  CHECK(later[0] == "echo:busy: processing");  // Marlin's keepalive, every 2 s
  CHECK(later[1] == "ok P15 B3");               // G4 leaves the queue (16 blocks hold 15 moves)
  CHECK(later[2] == "ok P14 B3");               // G1: now in the planner
}

// Marlin 2.0.7.2 (Linux HAL, BLOCK_BUFFER_SIZE 16, ADVANCED_OK) answered
// "ok P15 B3" idle: its ring buffer keeps one block empty.
TEST_CASE("virtual printer: a planner of 16 blocks takes 15 moves, the 16th waits for a block to end", "[serial]") {
  VirtualPrinterConfig c;
  c.advanced_ok = true;
  VirtualPrinter p(c);
  answers(p, 1);
  std::string moves;
  for (int i = 1; i <= 16; ++i) moves += "G1 X" + std::to_string(10 * i) + " F600\n";  // 1 s each
  p.receive(moves, 1);
  std::vector<std::string> at_once = answers(p, 1.5);
  REQUIRE(at_once.size() == 15);
  CHECK(at_once.back().rfind("ok P0 ", 0) == 0);
  CHECK(answers(p, 1.9).empty());      // the 16th waits for the first move
  CHECK(answers(p, 2.1).size() == 1);  // ... and enters when it ends
}

TEST_CASE("virtual printer: bytes beyond the RX buffer are lost while a command blocks", "[serial]") {
  VirtualPrinterConfig c;
  c.rx_buffer = 64;
  VirtualPrinter p(c);
  answers(p, 1);
  p.receive("M110 N0\n", 1);
  answers(p, 2);
  // M109 blocks; no line leaves the RX buffer until it is done.
  std::string burst = numbered(1, "M109 S200");
  for (int n = 2; n <= 8; ++n) burst += numbered(n, "G1 X1 Y2 Z3 E4");
  p.receive(burst, 2);
  answers(p, 3);
  CHECK(p.stats().overrun_bytes > 0);
  CHECK(p.stats().overrun_bytes == burst.size() - numbered(1, "M109 S200").size() - 63);
  answers(p, 60);
  // The line cut short is completed by the next one and fails its check.
  p.receive(numbered(9, "G90"), 60);
  std::vector<std::string> after = answers(p, 61);
  bool resend = false;
  for (const auto& line : after) resend = resend || line.rfind("Resend:", 0) == 0;
  CHECK(resend);
}

TEST_CASE("virtual printer: M105, M114, M115 answers, M112 halts at once", "[serial]") {
  VirtualPrinterConfig c;
  c.time_scale = 20;
  VirtualPrinter p(c);
  answers(p, 1);
  p.receive("M104 S200\nM105\nG1 X5 Y6 F6000\nM114\nM115\n", 1);
  std::vector<std::string> a = answers(p, 2);
  REQUIRE(a.size() >= 6);
  CHECK(a[0] == "ok");
  CHECK(a[1].rfind("ok T:", 0) == 0);
  CHECK(a[1].find("/200.00") != std::string::npos);
  CHECK(a[3].rfind("X:5.00 Y:6.00 Z:0.00 E:0.00", 0) == 0);
  CHECK(a[5].find("TIME_SCALE:20") != std::string::npos);
  p.receive("G4 S100\nM112\n", 2);
  std::vector<std::string> b = answers(p, 3);
  REQUIRE_FALSE(b.empty());
  CHECK(b.back() == "Error:Printer halted. kill() called!");
  CHECK(p.halted());
}

TEST_CASE("virtual printer options parse, bad ones are rejected", "[serial]") {
  VirtualPrinterConfig c;
  parse_virtual_options("baud=115200,queue=8,rx=256,planner=32,time-scale=20,advanced-ok,corrupt=0.01,seed=3", c);
  CHECK(c.baud == 115200);
  CHECK(c.queue == 8);
  CHECK(c.rx_buffer == 256);
  CHECK(c.planner == 32);
  CHECK(c.time_scale == 20);
  CHECK(c.advanced_ok);
  CHECK(c.corrupt == 0.01);
  CHECK(c.seed == 3);
  CHECK_THROWS_AS(parse_virtual_options("warp=9", c), std::invalid_argument);
  CHECK_THROWS_AS(parse_virtual_options("corrupt=2", c), std::invalid_argument);
  CHECK_THROWS_AS(parse_virtual_options("queue=1.5", c), std::invalid_argument);
  CHECK_THROWS_AS(parse_virtual_options("time-scale=0", c), std::invalid_argument);
  parse_virtual_options("speed-factor=1.25", c);
  CHECK(c.speed_factor == 1.25);
  CHECK_THROWS_AS(parse_virtual_options("speed-factor=0", c), std::invalid_argument);
}

TEST_CASE("virtual printer: speed-factor runs moves faster than their feed rates and M115 does not say",
          "[serial]") {
  // 10 mm at F600 is 1 s; at speed-factor 2 the block ends after 0.5 s.
  for (double factor : {1.0, 2.0}) {
    VirtualPrinterConfig c;
    c.speed_factor = factor;
    VirtualPrinter p(c);
    answers(p, 1);
    p.receive("G1 X10 F600\nM115\n", 1);
    std::vector<std::string> said = answers(p, 3);
    for (const std::string& a : said) CHECK(a.find("SPEED") == std::string::npos);
    CHECK(p.stats().last_move_end == Approx(1 + 1 / factor).margin(0.01));
  }
}

TEST_CASE("virtual printer: an over-long line is cut at MAX_CMD_SIZE and refused like Marlin does", "[serial]") {
  VirtualPrinter p(VirtualPrinterConfig{});
  answers(p, 1);
  p.receive("M110 N0\n" + numbered(1, "G90"), 1);
  CHECK(answers(p, 2) == std::vector<std::string>{"ok", "ok"});
  // 155 characters of M117 text: Marlin keeps 95 bytes, the checksum is cut off.
  std::string message = "M117 " + std::string(150, 'x');
  p.receive(numbered(2, message), 2);
  CHECK(answers(p, 3) ==
        std::vector<std::string>{"Error:No Checksum with line number, Last Line: 1", "Resend: 2", "ok"});
  // Lines glued into one of 33 KB: longer than the RX buffer, read as it
  // arrives by an idle printer, so nothing overruns and it is refused too.
  std::string glued;
  while (glued.size() < 33000) glued += "G1 X10.123 Y20.456 E0.01234 ";
  p.receive(numbered(2, glued), 3);
  CHECK(answers(p, 10) ==
        std::vector<std::string>{"Error:No Checksum with line number, Last Line: 1", "Resend: 2", "ok"});
  CHECK(p.stats().overrun_bytes == 0);
  // A line that fits goes through: 95 bytes with N and checksum.
  std::string fits = numbered(2, "M117 " + std::string(95 - 12, 'y'));
  REQUIRE(fits.size() == 96);
  p.receive(fits, 10);
  CHECK(answers(p, 11) == std::vector<std::string>{"ok"});
  CHECK(p.stats().accepted_lines == 2);
}

TEST_CASE("virtual printer: max-line sets MAX_CMD_SIZE which M115 reports and report-link=off hides the link", "[serial]") {
  VirtualPrinterConfig c;
  parse_virtual_options("max-line=40,report-link=off", c);
  CHECK(c.max_line == 40);
  CHECK_FALSE(c.report_link);
  VirtualPrinter p(c);
  answers(p, 1);
  p.receive("M115\n", 1);
  std::vector<std::string> a = answers(p, 2);
  REQUIRE_FALSE(a.empty());
  CHECK(a[0].rfind("FIRMWARE_NAME:Marlin", 0) == 0);
  CHECK(a[0].find("BAUD:") == std::string::npos);
  CHECK(a[0].find("TIME_SCALE:") == std::string::npos);
  CHECK(std::find(a.begin(), a.end(), "Cap:MAX_CMD_SIZE:40") != a.end());
  p.receive("M110 N0\n" + numbered(1, "M117 " + std::string(40, 'z')), 2);
  CHECK(answers(p, 3) ==
        std::vector<std::string>{"ok", "Error:No Checksum with line number, Last Line: 0", "Resend: 1", "ok"});
}
