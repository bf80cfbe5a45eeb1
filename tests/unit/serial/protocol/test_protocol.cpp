// Line format, checksums and the classification of printer answers
// (gcode/serial/protocol/protocol.hpp), and the flow-control rules (flow_control.hpp).
#include <catch2/catch.hpp>

#include <string>

#include "gcode/serial/protocol/flow_control.hpp"
#include "gcode/serial/protocol/protocol.hpp"

using namespace gcode::serial;

TEST_CASE("serial checksum is the XOR of every byte before the star", "[serial]") {
  // The handshake line every Marlin host sends; its checksum is well known.
  CHECK(checksum("N0 M110 N0") == 125);
  std::string out;
  append_numbered_line(out, 0, "M110 N0");
  CHECK(out == "N0 M110 N0*125\n");
  out.clear();
  append_numbered_line(out, 12345, "G1 X1.5 Y-2 E.3");
  std::uint8_t x = 0;
  for (char c : std::string("N12345 G1 X1.5 Y-2 E.3")) x ^= static_cast<std::uint8_t>(c);
  CHECK(out == "N12345 G1 X1.5 Y-2 E.3*" + std::to_string(x) + "\n");
}

TEST_CASE("serial command_for_sending takes paren comments out of the code", "[serial]") {
  std::string scratch;
  auto sent = [&](const char* text) { return std::string(command_for_sending(gcode::Line::parse(text), scratch)); };
  CHECK(sent("G1 X1 (note) Y2") == "G1 X1 Y2");
  CHECK(sent("G1 X1 (a)(b) Y2 ; c") == "G1 X1 Y2");
  CHECK(sent("G1 X1(a)Y2") == "G1 X1 Y2");
  CHECK(sent("N5 G1 X1 (a;b) Y2*12") == "G1 X1 Y2");  // the ';' inside is the comment's text
  CHECK(sent("G1 X1 ; (a) Y2") == "G1 X1");
  CHECK(sent("(a;b)") == "");
  CHECK(sent("G1 X1 Y2 ; plain") == "G1 X1 Y2");
  CHECK(sent("(only a comment)") == "");
  CHECK(sent("G1 X1 (unclosed") == "G1 X1");
  CHECK(sent("M117 Layer 3 (of 40)") == "M117 Layer 3 (of 40)");
}

TEST_CASE("serial command_for_sending drops an existing number and checksum", "[serial]") {
  CHECK(command_for_sending("G1 X1") == "G1 X1");
  CHECK(command_for_sending("  N17 G1 X1*99") == "G1 X1");
  CHECK(command_for_sending("N17 G1 X1 *99 ") == "G1 X1");
  CHECK(command_for_sending("M117 5*3 is 15") == "M117 5*3 is 15");
  CHECK(command_for_sending("") == "");
  CHECK(command_for_sending("\tG1 X1\r") == "G1 X1");  // blanks and a CRLF's CR
}

TEST_CASE("serial command_for_sending keeps control bytes for the line check to see", "[serial]") {
  using namespace std::string_literals;
  CHECK(command_for_sending("\0\0\rIHDR"s) == "\0\0\rIHDR"s);
  CHECK(command_for_sending("G1 X1\0"s) == "G1 X1\0"s);
  CHECK(command_for_sending("\x1bG1") == "\x1bG1");
}

TEST_CASE("serial ok answers, plain and ADVANCED_OK", "[serial]") {
  Response r = parse_response("ok");
  CHECK(r.kind == ResponseKind::Ok);
  CHECK(r.line == -1);
  r = parse_response("ok N12 P15 B3\r");
  CHECK(r.kind == ResponseKind::Ok);
  CHECK(r.line == 12);
  CHECK(r.planner_free == 15);
  CHECK(r.queue_free == 3);
  r = parse_response("ok T:210.0 /210.0 B:60.1 /60.0 @:64 B@:0");
  CHECK(r.kind == ResponseKind::Ok);
  CHECK(r.has_temperature);
  CHECK(r.queue_free == -1);
  CHECK(parse_response("OK").kind == ResponseKind::Ok);
  CHECK(parse_response("okay then").kind == ResponseKind::Unknown);
}

TEST_CASE("serial resend requests in every spelling", "[serial]") {
  for (const char* s : {"Resend: 42", "Resend:42", "resend 42", "RESEND: 42", "rs 42", "rs N42", "rs:42"}) {
    Response r = parse_response(s);
    INFO(s);
    CHECK(r.kind == ResponseKind::Resend);
    CHECK(r.line == 42);
  }
}

TEST_CASE("serial errors are classified: resend-related, recoverable, fatal", "[serial]") {
  Response r = parse_response("Error:checksum mismatch, Last Line: 41");
  CHECK(r.kind == ResponseKind::Error);
  CHECK(r.error == ErrorClass::Resend);
  CHECK(parse_response("Error:Line Number is not Last Line Number+1, Last Line: 41").error == ErrorClass::Resend);
  CHECK(parse_response("Error:No Checksum with line number, Last Line: 41").error == ErrorClass::Resend);
  CHECK(parse_response("Error:Printer halted. kill() called!").error == ErrorClass::Fatal);
  CHECK(parse_response("Error:Thermal Runaway, system stopped! Heater_ID: 0").error == ErrorClass::Fatal);
  CHECK(parse_response("Error:MAXTEMP triggered, system stopped! Heater_ID: 0").error == ErrorClass::Fatal);
  CHECK(parse_response("!! Shutdown due to webhooks request").error == ErrorClass::Fatal);
  CHECK(parse_response("Error:Busy: some message").error == ErrorClass::Recoverable);
}

TEST_CASE("serial busy, echo, actions, temperatures and the rest", "[serial]") {
  CHECK(parse_response("echo:busy: processing").kind == ResponseKind::Busy);
  CHECK(parse_response("busy: paused for user").kind == ResponseKind::Busy);
  CHECK(parse_response("echo:Unknown command: \"X\"").kind == ResponseKind::Echo);
  CHECK(parse_response("// Klipper state: Ready").kind == ResponseKind::Echo);
  Response a = parse_response("//action:pause");
  CHECK(a.kind == ResponseKind::Action);
  CHECK(a.text == "pause");
  CHECK(parse_response(" T:201.2 /210.0 B:60.0 /60.0 @:127 B@:0 W:3").kind == ResponseKind::Temperature);
  CHECK(parse_response("T0:200.0 /200.0").kind == ResponseKind::Temperature);
  CHECK(parse_response("wait").kind == ResponseKind::Wait);
  CHECK(parse_response("start").kind == ResponseKind::Start);
  CHECK(parse_response("Cap:ADVANCED_OK:1").kind == ResponseKind::Capability);
  CHECK(parse_response("").kind == ResponseKind::Empty);
  CHECK(parse_response("#$%&()+-<=>?").kind == ResponseKind::Unknown);
}

TEST_CASE("flow control: ping-pong keeps one line in flight", "[serial]") {
  FlowControl f(FlowMode::PingPong, 4, 128);
  CHECK(f.may_send(0, 0, 30));
  CHECK_FALSE(f.may_send(1, 30, 10));
}

TEST_CASE("flow control: window counts lines and bytes, one byte short of the buffer", "[serial]") {
  FlowControl f(FlowMode::Window, 4, 128);
  CHECK(f.may_send(0, 0, 500));   // a line longer than the buffer still goes alone
  CHECK(f.may_send(3, 90, 37));   // 127 bytes: fits Marlin's ring buffer
  CHECK_FALSE(f.may_send(3, 90, 38));
  CHECK_FALSE(f.may_send(4, 40, 10));  // the queue is full
}

TEST_CASE("flow control: advanced-ok learns the queue from B, auto switches on it", "[serial]") {
  FlowControl f(FlowMode::AdvancedOk, 4, 1024);
  CHECK_FALSE(f.ok_numbers_acknowledge());
  Response ok = parse_response("ok P15 B7");  // BUFSIZE 8, only the acknowledged command queued
  f.on_ok(ok);
  CHECK(f.queue() == 8);
  CHECK(f.may_send(7, 70, 10));
  CHECK_FALSE(f.may_send(8, 80, 10));
  f.on_ok(parse_response("ok N5 P0 B0"));  // a full queue says less; the size stays
  CHECK(f.queue() == 8);
  CHECK(f.ok_numbers_acknowledge());

  FlowControl a(FlowMode::Auto, 4, 128);
  CHECK(a.effective() == FlowMode::Window);
  a.on_ok(parse_response("ok N1 P15 B3"));
  CHECK(a.effective() == FlowMode::AdvancedOk);
  FlowControl plain(FlowMode::Auto, 4, 128);
  plain.on_ok(parse_response("ok"));
  CHECK(plain.effective() == FlowMode::Window);
  CHECK(parse_flow_mode("window") == FlowMode::Window);
  CHECK_FALSE(parse_flow_mode("fast").has_value());
}

TEST_CASE("protocol: what each line of the answer to M115 says", "[serial][protocol]") {
  FirmwareInfo info;
  CapabilityLine said = read_capability(
      "FIRMWARE_NAME:Marlin 2.1.2 (gc-virtual-printer) SOURCE_CODE_URL:github.com/MarlinFirmware/Marlin "
      "PROTOCOL_VERSION:1.0 MACHINE_TYPE:Virtual EXTRUDER_COUNT:1 TIME_SCALE:20 BAUD:250000",
      info);
  CHECK(said.names_firmware);
  CHECK_FALSE(said.max_line);
  CHECK(info.name == "Marlin 2.1.2 (gc-virtual-printer)");
  CHECK(info.time_scale == 20);
  CHECK(info.baud == 250000);
  CHECK_FALSE(read_capability("Cap:ADVANCED_OK:0", info).names_firmware);
  CHECK_FALSE(info.advanced_ok);
  read_capability("Cap:ADVANCED_OK:1", info);
  read_capability("Cap:EMERGENCY_PARSER:1", info);
  read_capability("Cap:AUTOREPORT_TEMP:1", info);
  CHECK(info.advanced_ok);
  CHECK(info.emergency_parser);
  CHECK(info.autoreport_temp);
  CHECK_FALSE(info.busy_protocol);
  read_capability("Cap:HOST_ACTION_COMMANDS:1", info);
  CHECK(info.busy_protocol);
  CHECK(read_capability("Cap:MAX_CMD_SIZE:96", info).max_line);
  CHECK(info.max_line == 96);
  CHECK_FALSE(read_capability("Cap:MAX_CMD_SIZE:8", info).max_line);  // too small to be true
  CHECK(info.max_line == 96);
  FirmwareInfo real;
  read_capability("FIRMWARE_NAME:Marlin bugfix-2.1.x (Jan 1 2024) SOURCE_CODE_URL:github.com/MarlinFirmware/Marlin", real);
  CHECK(real.name == "Marlin bugfix-2.1.x (Jan 1 2024)");
  CHECK(real.time_scale == 0);  // a real firmware names neither
  CHECK(real.baud == 0);
}

TEST_CASE("protocol: Klipper's, Prusa's and RepRapFirmware's answers, and a greeting after a NUL", "[serial][protocol]") {
  // Klipper (klippy/gcode.py): errors "!! ..." then ok; unknown commands
  // and its state as "// ..." lines.
  Response r = parse_response("!! Must home axis first: 0.000 200.000 19.960 [1357.946]");
  CHECK(r.kind == ResponseKind::Error);
  CHECK(r.error == ErrorClass::Recoverable);
  r = parse_response("// Unknown command:\"M201\"");
  CHECK(r.kind == ResponseKind::Echo);
  CHECK(r.unknown_command);
  CHECK(parse_response("echo:Unknown command: \"FOO\"").unknown_command);  // Marlin's
  // Real Marlin, a numbered line whose "N" was lost on the way: line noise,
  // not a command it refuses (the next line's number error brings it again).
  r = parse_response("echo:Unknown command: \"95767 G1 X101.2 Y88.4 E0.0123*87\"");
  CHECK(r.kind == ResponseKind::Echo);
  CHECK(r.lost_number);
  CHECK_FALSE(r.unknown_command);
  CHECK_FALSE(parse_response("echo:Unknown command: \"FOO\"").lost_number);
  CHECK_FALSE(parse_response("echo:SD card ok").unknown_command);
  r = parse_response("// Klipper state: Shutdown");
  CHECK(r.kind == ResponseKind::Error);
  CHECK(r.error == ErrorClass::Fatal);
  CHECK(parse_response("// Klipper state: Ready").kind == ResponseKind::Echo);
  CHECK(parse_response("!! Shutdown due to M112 command").error == ErrorClass::Fatal);
  // Its M115 answer is an ok line; TIME_SCALE: is no temperature.
  r = parse_response("ok FIRMWARE_NAME:Klipper FIRMWARE_VERSION:v0.12.0 TIME_SCALE:20 BAUD:250000");
  CHECK(r.kind == ResponseKind::Ok);
  CHECK_FALSE(r.has_temperature);
  CHECK(parse_response("ok T:20.0 /0.0 B:20.0 /0.0").has_temperature);
  CHECK(parse_response("ok T0:20.0 /0.0").has_temperature);
  // Prusa-Firmware (messages.c): a blank after the slashes.
  r = parse_response("// action:paused");
  CHECK(r.kind == ResponseKind::Action);
  CHECK(r.text == "paused");
  CHECK(parse_response("//action:pause").text == "pause");
  // RepRapFirmware: "rs n" asks for a line again; a heater fault stops.
  r = parse_response("rs 12");
  CHECK(r.kind == ResponseKind::Resend);
  CHECK(r.line == 12);
  CHECK(parse_response("Error: Heater 1 fault: temperature rising too slowly").error == ErrorClass::Fatal);
  CHECK(parse_response("Error: G0/G1: insufficient axes homed").error == ErrorClass::Recoverable);
  // A USB-serial chip's NUL before Marlin's greeting.
  CHECK(parse_response(std::string("\0start", 6)).kind == ResponseKind::Start);
}

TEST_CASE("protocol: a line the board's reset cut short, its greeting right after, is the greeting",
          "[serial][protocol]") {
  // What went out of the line it was sending, then "start": the ok must not
  // count, and the reset must not pass unseen.
  for (const char* cut : {"okstart", "ok N12 Pstart", "ok N12 P15 B3start", "ok T:20start", "echo:busy:start",
                          "T:201.2 /210.0 B:6start", "Resend: 1start", "Error:checkstart", "ostart"}) {
    Response r = parse_response(cut);
    INFO(cut);
    CHECK(r.kind == ResponseKind::Start);
    CHECK(r.text == "start");
    CHECK(is_restart_line(cut));
  }
  // Whole lines that end so are not.
  CHECK(parse_response("//action:start").kind == ResponseKind::Action);
  CHECK(parse_response("// action:start").kind == ResponseKind::Action);
  CHECK(parse_response("echo:Please restart").kind == ResponseKind::Echo);
  CHECK(parse_response("Restart").kind == ResponseKind::Unknown);
  CHECK(parse_response("ok").kind == ResponseKind::Ok);
  CHECK(!is_restart_line("echo:Please RESTART"));
}

TEST_CASE("protocol: the firmware's name from Klipper's, Prusa's and RepRapFirmware's M115", "[serial][protocol]") {
  FirmwareInfo k;
  CHECK(read_capability("ok FIRMWARE_NAME:Klipper FIRMWARE_VERSION:v0.12.0-253-g1e3d9aaf", k).names_firmware);
  CHECK(k.name == "Klipper");
  FirmwareInfo p;
  read_capability("FIRMWARE_NAME:Prusa-Firmware 3.13.3 based on Marlin FIRMWARE_URL:https://github.com/prusa3d/"
                  "Prusa-Firmware PROTOCOL_VERSION:1.0 MACHINE_TYPE:Prusa i3 MK3S EXTRUDER_COUNT:1",
                  p);
  CHECK(p.name == "Prusa-Firmware 3.13.3 based on Marlin");
  FirmwareInfo d;
  read_capability("FIRMWARE_NAME: RepRapFirmware for Duet 3 MB6HC FIRMWARE_VERSION: 3.5.1 ELECTRONICS: Duet 3 MB6HC "
                  "v1.01 FIRMWARE_DATE: 2024-04-19 14:39:52",
                  d);
  CHECK(d.name == "RepRapFirmware for Duet 3 MB6HC");
}
