// The virtual printer's link (serial/virtual_wire.hpp) and its Marlin
// dialect (serial/virtual_dialect.hpp).
#include <catch2/catch.hpp>

#include "gcode/serial/sim/virtual_dialect.hpp"
#include "gcode/serial/sim/virtual_printer_options.hpp"
#include "gcode/serial/sim/virtual_wire.hpp"

using namespace gcode::serial;

TEST_CASE("virtual wire: bytes arrive one byte time apart, after what is on the way", "[serial][virtual_wire]") {
  VirtualWire w(10000);  // 1000 bytes a second: 1 ms a byte
  CHECK(w.next_arrival() == VirtualWire::kNever);
  w.receive("ab", 1.0);
  CHECK(w.next_arrival() == Approx(1.001));
  w.receive("c", 1.0005);  // behind the others
  CHECK(w.arrive() == 'a');
  CHECK(w.next_arrival() == Approx(1.002));
  CHECK(w.arrive() == 'b');
  CHECK(w.arrive() == 'c');
  CHECK(w.next_arrival() == VirtualWire::kNever);
  w.receive("d", 1.0);  // written before the last byte arrived: after it
  CHECK(w.next_arrival() == Approx(1.004));
}

TEST_CASE("virtual wire: the host gets whole bytes as they are sent", "[serial][virtual_wire]") {
  VirtualWire w(10000);
  w.transmit("ok", 2.0);     // 3 bytes: until 2.003
  w.transmit("wait", 2.0);   // after it: until 2.008
  CHECK(w.transmitted(2.0) == "");
  CHECK(w.transmitted(2.002) == "ok");
  CHECK(w.next_line_sent() == Approx(2.003));
  CHECK(w.transmitted(2.003) == "ok\n");
  w.take(3);
  CHECK(w.next_line_sent() == Approx(2.008));
  CHECK(w.transmitted(3) == "wait\n");
  w.take(5);
  CHECK(w.transmitted(3) == "");
  CHECK(w.next_line_sent() == VirtualWire::kNever);
}

TEST_CASE("virtual dialect: Marlin's own texts", "[serial][virtual_wire]") {
  const ReplyDialect& d = marlin_dialect();
  CHECK(d.greeting() == "start");
  CHECK(d.ok(7, false, 3, 2) == "ok");
  CHECK(d.ok(7, true, 15, 3) == "ok N7 P15 B3");
  CHECK(d.ok(-1, true, 15, 3) == "ok P15 B3");
  CHECK(d.rejected(LineFault::Checksum, 41) ==
        std::vector<std::string>{"Error:checksum mismatch, Last Line: 41", "Resend: 42", "ok"});
  CHECK(d.rejected(LineFault::LineNumber, 5).front() ==
        "Error:Line Number is not Last Line Number+1, Last Line: 5");
  CHECK(d.rejected(LineFault::NoChecksum, 5).front() == "Error:No Checksum with line number, Last Line: 5");
  CHECK(d.rejected(LineFault::NoLineNumber, 5).front() == "Error:No Line Number with checksum, Last Line: 5");
  CHECK(d.busy() == "echo:busy: processing");
  CHECK(d.unknown_command("SET_FAN_SPEED FAN=x") == "echo:Unknown command: \"SET_FAN_SPEED FAN=x\"");
  Temperatures t{150, 200, 60, 60};
  CHECK(d.temperatures(t, true) == "T:150.00 /200.00 B:60.00 /60.00 @:127 B@:0 W:?");
  CHECK(d.temperature_ok(t) == "ok T:150.00 /200.00 B:60.00 /60.00 @:127 B@:0");
  CHECK(d.halted() == "Error:Printer halted. kill() called!");
  VirtualPrinterConfig c;
  c.report_link = false;
  c.advanced_ok = true;
  std::vector<std::string> report = d.firmware_report(c);
  CHECK(report.front() ==
        "FIRMWARE_NAME:Marlin 2.1.2 (gc-virtual-printer) SOURCE_CODE_URL:github.com/MarlinFirmware/Marlin "
        "PROTOCOL_VERSION:1.0 MACHINE_TYPE:Virtual EXTRUDER_COUNT:1");
  CHECK(report[2] == "Cap:ADVANCED_OK:1");
  CHECK(report.back() == "Cap:MAX_CMD_SIZE:96");
}
