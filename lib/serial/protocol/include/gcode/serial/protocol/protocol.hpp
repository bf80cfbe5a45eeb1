#pragma once
// The text protocol of Marlin-style firmware (also RepRapFirmware, Repetier
// and Klipper where they differ): numbered lines with an XOR checksum going
// out, and the printer's answers coming back.
//
// Out: "N<n> <command>*<checksum>\n", checksum = XOR of every byte before '*'.
// In:  "ok [N<n> P<planner free> B<queue free>] [T:... B:...]", "Resend: n" or
//      "rs n", "Error:...", "echo:busy: processing", "echo:...", "//action:...",
//      temperature reports "T:210.0 /210.0 B:60.0 /60.0", "wait", "start".
#include <cstdint>
#include <string>
#include <string_view>

#include "gcode/core/line.hpp"

namespace gcode::serial {

// XOR of all bytes of `text` (Marlin's and RepRap's line checksum).
std::uint8_t checksum(std::string_view text);

// Appends "N<number> <command>*<checksum>\n" to `out`.
void append_numbered_line(std::string& out, long long number, std::string_view command);
// The command of such a line: "N12 G1 X1*34\n" -> "G1 X1".
std::string_view command_of_numbered(std::string_view wire);

enum class ResponseKind : std::uint8_t {
  Empty,        // a blank line
  Ok,
  Resend,       // "Resend: n", "rs n"
  Error,        // "Error:...", Klipper's "!! ..."
  Busy,         // "busy: processing" (with or without "echo:")
  Echo,         // "echo:..." and Klipper's "// ..." messages
  Action,       // "//action:pause" and friends (Prusa: "// action:paused")
  Temperature,  // an autoreport or M105 answer on its own line
  Wait,         // Repetier/Marlin "wait" while idle
  Start,        // the greeting after a reset
  Capability,   // M115 "Cap:NAME:1" and the FIRMWARE_NAME line
  Unknown,
};

enum class ErrorClass : std::uint8_t {
  None,
  Resend,       // checksum / line number trouble: a "Resend:" follows
  Recoverable,  // an unknown command and the like: logged, printing goes on
  Fatal,        // "Printer halted", "kill()", thermal runaway: stop
};

struct Response {
  ResponseKind kind = ResponseKind::Empty;
  long long line = -1;      // Resend: the line asked for; Ok: the N of ADVANCED_OK
  int planner_free = -1;    // ADVANCED_OK P
  int queue_free = -1;      // ADVANCED_OK B
  bool has_temperature = false;  // "ok T:..." (the answer to M105)
  ErrorClass error = ErrorClass::None;
  bool unknown_command = false;  // Echo: the firmware does not know a command it was sent
  // Echo: the "unknown command" is a numbered line whose N was lost on the
  // way (real Marlin: 'Unknown command: "95767 G1 X1"'): line noise, not a
  // command the firmware refuses; the next line's number error brings it again.
  bool lost_number = false;
  std::string_view text;    // the line without its prefix (error message, action name, ...)
};

// Classifies one received line (without its ending). Never fails: anything
// not recognised is Unknown, and the caller logs it.
Response parse_response(std::string_view line);
// Whether a line says the board has just restarted: its greeting ("start",
// "\0start" from the byte a USB chip sends as it comes up, or a line the
// reset cut short with the greeting after it: "ok N12 Pstart") or Marlin's
// boot note of why ("echo: External Reset", "Watchdog Reset", ...).
bool is_restart_line(std::string_view line);
bool is_reset_note(std::string_view text);

ErrorClass classify_error(std::string_view message);
// Whether a message says a move was refused because the printer is not
// homed: Marlin's "Home XYZ First" (or "Home X First"), Klipper's "Must
// home axis first: ...", RepRapFirmware's "G0/G1: insufficient axes homed".
bool says_not_homed(std::string_view message);
// Whether an error says a homing failed, whichever command it answers (a
// start macro that homes): Klipper's "No trigger on x after full movement",
// "Endstop x still triggered after retract", "Probe triggered prior to
// movement"; "Homing failed".
bool says_homing_failed(std::string_view message);

// The code of a G-code line as it goes to the firmware: comment and blanks
// gone, an existing "N123 " prefix and "*71" checksum removed (the sender
// numbers lines itself).
std::string_view command_for_sending(std::string_view code);
// The same for a parsed line, with "(...)" comments inside the code taken
// out too: "G1 X1 (note) Y2" sends "G1 X1 Y2", never a command cut at its
// comment. `scratch` holds the text when it had to be rebuilt.
std::string_view command_for_sending(const Line& line, std::string& scratch);

// What a firmware says of itself in its answer to M115.
struct FirmwareInfo {
  std::string name;              // FIRMWARE_NAME
  bool advanced_ok = false;
  bool emergency_parser = false;
  bool autoreport_temp = false;
  bool busy_protocol = false;
  double time_scale = 0;         // TIME_SCALE: a simulated printer runs this much faster
  double baud = 0;               // BAUD: a simulated printer's link rate
  std::size_t max_line = 0;      // Cap:MAX_CMD_SIZE (Marlin does not report it)
};

// What one line of that answer told.
struct CapabilityLine {
  bool names_firmware = false;   // the FIRMWARE_NAME line: name, time_scale and baud set
  bool max_line = false;         // "Cap:MAX_CMD_SIZE:n" with a usable n (16 or more)
};
// Adds one line of the answer to M115 to `info`: the FIRMWARE_NAME line
// ("FIRMWARE_NAME:Marlin 2.1.2 SOURCE_CODE_URL:... TIME_SCALE:20 BAUD:250000",
// Klipper's "ok FIRMWARE_NAME:Klipper FIRMWARE_VERSION:v0.12.0", RepRapFirmware's
// "FIRMWARE_NAME: RepRapFirmware for Duet 3 MB6HC FIRMWARE_VERSION: 3.5.1"),
// or "Cap:NAME:1" lines (ADVANCED_OK, EMERGENCY_PARSER, AUTOREPORT_TEMP,
// BUSY_PROTOCOL or HOST_ACTION_COMMANDS, MAX_CMD_SIZE).
CapabilityLine read_capability(std::string_view text, FirmwareInfo& info);

}  // namespace gcode::serial
