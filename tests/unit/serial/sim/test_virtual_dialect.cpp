// Each firmware's replies and ways in the virtual printer
// (gcode/serial/sim/virtual_dialect.hpp): Klipper's pseudo-terminal, Prusa's
// own pause and silent waits, RepRapFirmware's errors and "rs n". The
// expected lines follow each firmware's own wording (klippy/gcode.py and
// toolhead.py, Prusa-Firmware's messages.c, Duet3D's G-code reference).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/serial/sim/virtual_dialect.hpp"
#include "gcode/serial/sim/virtual_printer.hpp"
#include "gcode/serial/sim/virtual_printer_options.hpp"
#include "printer_talk.hpp"

using namespace gcode::serial;
using gctest::answers;
using gctest::numbered;
using Lines = std::vector<std::string>;

namespace {

VirtualPrinterConfig flavour(const char* name) {
  VirtualPrinterConfig c;
  c.firmware = name;
  c.report_link = false;
  return c;
}

}  // namespace

TEST_CASE("virtual dialects by name, firmware= and user-seconds= options", "[serial][dialect]") {
  CHECK(find_dialect("marlin2") == &marlin_dialect());
  CHECK(find_dialect("marlin") == &marlin1_dialect());  // slicers' name for Marlin 1
  CHECK(find_dialect("Klipper") == &klipper_dialect());
  CHECK(find_dialect("prusa") == &prusa_dialect());
  CHECK(find_dialect("rrf") == &rrf_dialect());
  CHECK(find_dialect("reprapfirmware") == &rrf_dialect());
  CHECK(find_dialect("smoothie") == nullptr);
  VirtualPrinterConfig c;
  parse_virtual_options("firmware=klipper,user-seconds=12", c);
  CHECK(c.firmware == "klipper");
  CHECK(c.user_seconds == 12);
  CHECK_THROWS_AS(parse_virtual_options("firmware=smoothie", c), std::invalid_argument);
}

TEST_CASE("virtual Klipper: no greeting, numbers ignored, unknown commands and moves before homing answered with ok",
          "[serial][dialect]") {
  VirtualPrinter p(flavour("klipper"));
  CHECK(answers(p, 1).empty());  // a pseudo-terminal greets nobody
  // Wrong numbers, a wrong checksum, M110: all taken as they are.
  p.receive("M110 N0\nN7 G90*1\n" + numbered(3, "G91") + "M201 X1000\nG1 X10 F600\n", 1);
  CHECK(answers(p, 2) == Lines{"ok", "ok", "ok", "// Unknown command:\"M201\"", "ok",
                               "!! Must home axis first: 0.000 0.000 0.000 [0.000]", "ok"});
  CHECK(p.stats().checksum_errors == 0);
  CHECK(p.stats().line_number_errors == 0);
  p.receive("M115\nM105\nM114\n", 2);
  CHECK(answers(p, 3) == Lines{"ok FIRMWARE_NAME:Klipper FIRMWARE_VERSION:v0.12.0-gc-virtual-printer",
                               "ok B:20.0 /0.0 T0:20.0 /0.0", "X:0.000 Y:0.000 Z:0.000 E:0.000", "ok"});
}

// klippy v0.13 (unmodified, simulated board, no [display] / [respond] /
// second extruder) answered each of these so.
TEST_CASE("virtual Klipper without a display: M73, M117, M118 and T0 are unknown commands, with their ok",
          "[serial][dialect]") {
  VirtualPrinter p(flavour("klipper"));
  p.receive("M117 Paused at layer 3\nM73 P10\nM118 hi\nT0\n", 1);
  CHECK(answers(p, 2) == Lines{"// Unknown command:\"M117\"", "ok", "// Unknown command:\"M73\"", "ok",
                               "// Unknown command:\"M118\"", "ok", "// Unknown command:\"T0\"", "ok"});
}

TEST_CASE("virtual Klipper: moves answered at once until about 1 s of motion is queued, no busy while homing",
          "[serial][dialect]") {
  VirtualPrinterConfig c = flavour("klipper");
  c.planner = 2;  // Marlin's planner size plays no part
  VirtualPrinter p(c);
  p.receive("G28\n", 0);
  Lines homed = answers(p, 4);  // 3 s of homing, not a word until its ok
  CHECK(homed == Lines{"ok"});
  // Six moves of 0.5 s each (10 mm at 1200 mm/min): three are answered at
  // once (up to 1 s queued, as klippy measured), the fourth once the first
  // has run, then one each half second.
  for (int i = 1; i <= 6; ++i) p.receive("G1 X" + std::to_string(10 * i) + " F1200\n", 4);
  CHECK(answers(p, 4.01).size() == 3);
  CHECK(answers(p, 4.6).size() == 1);
  CHECK(answers(p, 5.6).size() == 2);
}

TEST_CASE("virtual printer: home-fails and unhome-after, on Klipper and on Marlin", "[serial][dialect]") {
  VirtualPrinterConfig c = flavour("klipper");
  parse_virtual_options("home-fails,unhome-after=3", c);
  CHECK(c.home_fails);
  CHECK(c.unhome_after == 3);
  CHECK_THROWS_AS(parse_virtual_options("unhome-after=-1", c), std::invalid_argument);
  // Klipper: the homing error, then G28's ok; unhomed, the move is refused.
  c = flavour("klipper");
  c.home_fails = true;
  VirtualPrinter k(c);
  k.receive("G28\nG1 X10 F600\n", 0);
  CHECK(answers(k, 5) == Lines{"!! No trigger on x after full movement", "ok",
                               "!! Must home axis first: 0.000 0.000 0.000 [0.000]", "ok"});
  CHECK_FALSE(k.homed());
  // Homed, then its motors go off after the third command.
  c = flavour("klipper");
  c.unhome_after = 3;
  VirtualPrinter u(c);
  u.receive("G28\nG1 X10 F600\nG1 X20\nG1 X30\n", 0);
  Lines a = answers(u, 10);
  CHECK(a == Lines{"ok", "ok", "ok", "!! Must home axis first: 20.000 0.000 0.000 [0.000]", "ok"});
  CHECK_FALSE(u.homed());
  // Marlin: kill(), then silence.
  c = flavour("marlin2");
  c.home_fails = true;
  VirtualPrinter m(c);
  CHECK(answers(m, 1) == Lines{"start"});
  m.receive("G28\nG1 X10 F600\n", 1);
  // (3 s of homing, a keepalive after 2 s.)
  CHECK(answers(m, 6) == Lines{"echo:busy: processing", "Error:Printer halted. kill() called!"});
  CHECK(m.halted());
}

TEST_CASE("virtual Klipper: M112 shuts it down, every command refused with its ok until FIRMWARE_RESTART",
          "[serial][dialect]") {
  VirtualPrinter p(flavour("klipper"));
  p.receive("G28\nM112\n", 0);  // M112 overtakes the homing
  Lines a = answers(p, 1);
  REQUIRE(a.size() >= 1);
  CHECK(a[0] == "// Klipper state: Shutdown");
  CHECK(p.halted());
  answers(p, 5);
  p.receive("G1 X5\nM105\n", 5);
  Lines refused = answers(p, 6);
  REQUIRE(refused.size() >= 3);
  CHECK(refused[0] == "// Shutdown due to M112 command");
  CHECK(refused[refused.size() - 3] == "!! Shutdown due to M112 command");
  CHECK(refused[1] == "// Once the underlying issue is corrected, use the");  // klippy's own words
  CHECK(refused[refused.size() - 2] == "ok");
  CHECK(refused.back() == "ok T:0");  // M105 still answers, without heaters
  p.receive("FIRMWARE_RESTART\n", 6);
  // (The restart loses what was on its way, its ok too.)
  CHECK(answers(p, 7) == Lines{"// Klipper state: Ready"});
  CHECK_FALSE(p.halted());
  p.receive("G4 P10\n", 7);
  CHECK(answers(p, 8) == Lines{"ok"});
}

TEST_CASE("virtual Prusa: M601 answers, pauses after the moves, holds commands until the user resumes",
          "[serial][dialect]") {
  VirtualPrinterConfig c = flavour("prusa");
  c.user_seconds = 10;
  VirtualPrinter p(c);
  CHECK(answers(p, 1) == Lines{"start"});
  p.receive("M110 N0\n" + numbered(1, "G1 X10 F600") + numbered(2, "M601") + numbered(3, "G1 X20"), 1);
  CHECK(answers(p, 1.5) == Lines{"ok", "ok", "ok"});  // M601's ok comes first (its ClearToSend)
  Lines paused = answers(p, 5);                         // the move ends at 2 s, then the pause
  CHECK(paused == Lines{"// action:paused"});
  CHECK(answers(p, 11).empty());  // G1 X20 waits: not a word meanwhile
  CHECK(answers(p, 13) == Lines{"// action:resumed", "ok"});
}

TEST_CASE("virtual Prusa: M600 and M115 U<newer> wait for the user without busy, an older version just ok",
          "[serial][dialect]") {
  VirtualPrinterConfig c = flavour("prusa");
  c.user_seconds = 40;
  VirtualPrinter p(c);
  answers(p, 1);
  p.receive("M600\n", 1);
  CHECK(answers(p, 40).empty());  // no "echo:busy: processing"
  CHECK(answers(p, 42) == Lines{"ok"});
  p.receive("M115 U3.11.0\n", 42);
  CHECK(answers(p, 43) == Lines{"ok"});
  p.receive("M115 U3.99.0\n", 43);
  CHECK(answers(p, 72).empty());  // 30 s at most (the message times out)
  CHECK(answers(p, 74) == Lines{"ok"});
  p.receive("M115\n", 74);
  Lines report = answers(p, 75);
  REQUIRE_FALSE(report.empty());
  CHECK(report[0].rfind("FIRMWARE_NAME:Prusa-Firmware 3.13.3 based on Marlin FIRMWARE_URL:", 0) == 0);
  CHECK(report.back() == "ok");
  p.receive("G28\n", 75);
  CHECK(answers(p, 79) == Lines{"echo:busy: processing", "ok"});  // its keepalive works otherwise
}

TEST_CASE("virtual RepRapFirmware: rs after a bad line, Error: lines before their ok, no busy", "[serial][dialect]") {
  VirtualPrinter p(flavour("rrf"));
  CHECK(answers(p, 1).empty());
  p.receive("M110 N0\nN1 G90*99\n", 1);
  CHECK(answers(p, 2) == Lines{"ok", "rs 1", "ok"});
  p.receive(numbered(1, "M900 K0.05") + numbered(2, "G1 X5 F600") + numbered(3, "M115"), 2);
  CHECK(answers(p, 3) == Lines{"Error: M900: command is not supported", "ok", "Error: G0/G1: insufficient axes homed",
                               "ok",
                               "FIRMWARE_NAME: RepRapFirmware for Duet 3 MB6HC (gc-virtual-printer) FIRMWARE_VERSION: "
                               "3.5.1 ELECTRONICS: Duet 3 MB6HC v1.01 FIRMWARE_DATE: 2024-04-19",
                               "ok"});
  p.receive(numbered(4, "G4 S5"), 3);
  CHECK(answers(p, 8.1) == Lines{"ok"});  // 5 s without a word
}

TEST_CASE("virtual Marlin variants: a Resend without its ok, wait when idle", "[serial][dialect]") {
  VirtualPrinterConfig c;
  c.resend_ok = false;
  c.idle_wait = 1;
  VirtualPrinter p(c);
  CHECK(answers(p, 0.5) == Lines{"start"});
  CHECK(answers(p, 1.01) == Lines{"wait"});
  p.receive("M110 N0\nN2 G90*99\n", 1.5);
  CHECK(answers(p, 2) == Lines{"ok", "Error:Line Number is not Last Line Number+1, Last Line: 0", "Resend: 1"});
  CHECK(answers(p, 2.4).empty());  // a second after the last command
  CHECK(answers(p, 2.6) == Lines{"wait"});
  p.receive("G4 P3000\n", 2.6);
  CHECK(answers(p, 4.7) == Lines{"echo:busy: processing"});  // not idle: no wait
}
