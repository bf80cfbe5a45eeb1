#pragma once
// Whether a command can go to the firmware as it is, before it is sent.
//
// Marlin keeps at most MAX_CMD_SIZE - 1 bytes of a line (96 - 1 by default,
// "N<n> " and "*<checksum>" included) and skips the rest up to the newline,
// checksum and all: an over-long line is refused with "No Checksum with line
// number" and a resend request every time it is sent, so one such line would
// stall the print. Its serial reader also ends a line at CR, erases with
// backspace, ends the string at NUL and drops a backslash (an escape), so a
// line with control bytes, or a backslash, never matches its checksum either;
// binary junk is not G-code at all.
//
// So: an M117/M118 message that does not fit is shortened (the display or the
// host log loses its tail, the print goes on); any other line that does not
// fit, or that holds bytes the firmware cannot read, is refused, and the
// caller says so with the input line number.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace gcode::serial {

// Marlin's MAX_CMD_SIZE.
inline constexpr std::size_t kDefaultMaxLine = 96;

enum class LineProblem : std::uint8_t {
  None,
  Shortened,   // an M117/M118 message cut to fit
  Unreadable,  // a control byte, a backslash or bytes that are not UTF-8 text
  TooLong,     // longer than the firmware keeps, and not a message
};

struct LineCheck {
  LineProblem problem = LineProblem::None;
  std::string_view command;  // what to send (a prefix of the input when shortened); empty when refused
  std::size_t length = 0;    // the numbered line's bytes without its newline, as it came in
  std::size_t column = 0;    // Unreadable: 1-based position of the first bad byte in the command
  unsigned char byte = 0;    // Unreadable: that byte
};

// The bytes of "N<number> <command>*<checksum>" (without the newline).
std::size_t numbered_length(long long number, std::string_view command);

// Checks `command` (as command_for_sending returns it) for sending as line
// `number` to a firmware that keeps `max_line` - 1 bytes of a line.
LineCheck check_line(std::string_view command, long long number, std::size_t max_line);

// "M117 message shortened to 60 bytes ..." or why the line cannot be sent;
// empty for LineProblem::None.
std::string describe(const LineCheck& check, std::size_t max_line);

}  // namespace gcode::serial
