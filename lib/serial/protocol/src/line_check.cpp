#include "gcode/serial/protocol/line_check.hpp"

#include <fmt/format.h>

#include "gcode/serial/protocol/protocol.hpp"

namespace gcode::serial {

namespace {

std::size_t digits(unsigned long long v) {
  std::size_t n = 1;
  while (v >= 10) {
    v /= 10;
    ++n;
  }
  return n;
}

// "N<number> " and "*" around the command, and the checksum's digits.
std::size_t frame_length(long long number, std::uint8_t sum) {
  std::size_t n = number < 0 ? digits(static_cast<unsigned long long>(-number)) + 1
                             : digits(static_cast<unsigned long long>(number));
  return 1 + n + 1 + 1 + digits(sum);
}

bool continuation(unsigned char c) { return (c & 0xC0) == 0x80; }

// The length of the UTF-8 sequence at s[i], or 0 when it is not one
// (overlong forms, surrogates and code points above U+10FFFF included).
std::size_t utf8_sequence(std::string_view s, std::size_t i) {
  auto at = [&](std::size_t k) { return i + k < s.size() ? static_cast<unsigned char>(s[i + k]) : 0; };
  unsigned char c = at(0);
  if (c >= 0xC2 && c <= 0xDF) return continuation(at(1)) ? 2 : 0;
  if (c >= 0xE0 && c <= 0xEF) {
    unsigned char c1 = at(1);
    if (!continuation(c1) || !continuation(at(2))) return 0;
    if ((c == 0xE0 && c1 < 0xA0) || (c == 0xED && c1 > 0x9F)) return 0;
    return 3;
  }
  if (c >= 0xF0 && c <= 0xF4) {
    unsigned char c1 = at(1);
    if (!continuation(c1) || !continuation(at(2)) || !continuation(at(3))) return 0;
    if ((c == 0xF0 && c1 < 0x90) || (c == 0xF4 && c1 > 0x8F)) return 0;
    return 4;
  }
  return 0;
}

// The offset of the first byte the firmware would not read as it was sent, or npos.
std::size_t first_unreadable(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      if ((c < 0x20 && c != '\t') || c == 0x7F || c == '\\') return i;
      ++i;
      continue;
    }
    std::size_t n = utf8_sequence(s, i);
    if (n == 0) return i;
    i += n;
  }
  return std::string_view::npos;
}

// M117 (LCD message) and M118 (echo to the host) carry free text.
bool is_message(std::string_view command) {
  if (command.size() < 4 || (command[0] != 'M' && command[0] != 'm')) return false;
  if (command.substr(1, 3) != "117" && command.substr(1, 3) != "118") return false;
  return command.size() == 4 || command[4] < '0' || command[4] > '9';
}

}  // namespace

std::size_t numbered_length(long long number, std::string_view command) {
  std::string prefix = fmt::format("N{} ", number);
  std::uint8_t sum = static_cast<std::uint8_t>(checksum(prefix) ^ checksum(command));
  return frame_length(number, sum) + command.size();
}

LineCheck check_line(std::string_view command, long long number, std::size_t max_line) {
  LineCheck r;
  r.command = command;
  r.length = numbered_length(number, command);
  std::size_t bad = first_unreadable(command);
  if (bad != std::string_view::npos) {
    r.problem = LineProblem::Unreadable;
    r.column = bad + 1;
    r.byte = static_cast<unsigned char>(command[bad]);
    r.command = {};
    return r;
  }
  std::size_t keep = max_line > 0 ? max_line - 1 : 0;
  if (r.length <= keep) return r;
  if (!is_message(command)) {
    r.problem = LineProblem::TooLong;
    r.command = {};
    return r;
  }
  // Room for the text with the widest checksum (three digits).
  std::size_t frame = frame_length(number, 255);
  std::size_t room = keep > frame ? keep - frame : 0;
  if (room < 4) {
    r.problem = LineProblem::TooLong;
    r.command = {};
    return r;
  }
  std::size_t cut = room;
  // Never split a UTF-8 character; drop the blanks the cut leaves at the end.
  while (cut > 4 && continuation(static_cast<unsigned char>(command[cut]))) --cut;
  while (cut > 4 && (command[cut - 1] == ' ' || command[cut - 1] == '\t')) --cut;
  r.problem = LineProblem::Shortened;
  r.command = command.substr(0, cut);
  return r;
}

std::string describe(const LineCheck& check, std::size_t max_line) {
  std::size_t keep = max_line > 0 ? max_line - 1 : 0;
  switch (check.problem) {
    case LineProblem::None: return {};
    case LineProblem::Shortened:
      return fmt::format("{} message shortened to {} bytes: the printer keeps {} bytes of a line (--max-line {}), "
                         "this one would be {} with its line number and checksum",
                         check.command.substr(0, 4), check.command.size(), keep, max_line, check.length);
    case LineProblem::TooLong:
      return fmt::format("the line is {} bytes with its line number and checksum; the printer keeps {} (--max-line {}) "
                         "and would refuse it every time it is sent",
                         check.length, keep, max_line);
    case LineProblem::Unreadable:
      if (check.byte == '\\')
        return fmt::format("a backslash at column {}: Marlin reads it as an escape, so the line would never match "
                           "its checksum",
                           check.column);
      return fmt::format("byte 0x{:02X} at column {} is not G-code text (a control byte or binary data)", check.byte,
                         check.column);
  }
  return {};
}

}  // namespace gcode::serial
