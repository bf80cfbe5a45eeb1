#include "gcode/serial/protocol/protocol.hpp"

#include <charconv>
#include <cstdlib>
#include <string>

namespace gcode::serial {

namespace {

char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

bool starts_with_nocase(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (lower(s[i]) != lower(prefix[i])) return false;
  return true;
}

bool contains_nocase(std::string_view s, std::string_view needle) {
  if (needle.size() > s.size()) return false;
  for (std::size_t i = 0; i + needle.size() <= s.size(); ++i)
    if (starts_with_nocase(s.substr(i), needle)) return true;
  return false;
}

// White space and the NULs of a board's noisy boot, at either end.
std::string_view trim_noise(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r' || s.front() == '\0')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '\0')) s.remove_suffix(1);
  return s;
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

bool ends_with(std::string_view s, std::string_view tail) {
  return s.size() >= tail.size() && s.substr(s.size() - tail.size()) == tail;
}

// A board that resets while it is sending a line cuts it: the bytes that
// went out are followed by its greeting on the same line ("okstart",
// "ok N12 Pstart", "echo:busy:start"). Read as the greeting, or the reset
// would pass unseen. Not "restart" in a message, nor Marlin's host action
// "//action:start" said whole.
constexpr std::string_view kGreeting = "start";

bool cut_by_greeting(std::string_view s) {
  if (s.size() <= kGreeting.size() || !ends_with(s, kGreeting)) return false;
  std::string_view before = s.substr(0, s.size() - kGreeting.size());
  if (ends_with(before, "re") || ends_with(before, "Re") || ends_with(before, "RE")) return false;
  return !starts_with_nocase(s, "//action:start") && !starts_with_nocase(s, "// action:start");
}

// Blanks around a command, and the CR of a CRLF line; not other control
// bytes: a line that holds them is junk, and the sender must see it whole.
std::string_view trim_command(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// The first integer in `s` (after any non-digits), or -1.
long long first_integer(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size() && !is_digit(s[i])) ++i;
  long long v = -1;
  if (i < s.size()) std::from_chars(s.data() + i, s.data() + s.size(), v);
  return v;
}

// "ok N12 P15 B3 T:..." -> the ADVANCED_OK fields and whether temperatures follow.
void parse_ok_fields(std::string_view rest, Response& r) {
  std::size_t i = 0;
  while (i < rest.size()) {
    while (i < rest.size() && rest[i] == ' ') ++i;
    std::size_t start = i;
    while (i < rest.size() && rest[i] != ' ') ++i;
    std::string_view token = rest.substr(start, i - start);
    if (token.size() < 2) continue;
    if (token.find(':') != std::string_view::npos) {
      // "T:210.0", "B:60.0", "T0:210.0": a temperature report rides on this
      // ok (M105); not "TIME_SCALE:20" (Klipper's M115 answer is an ok line).
      std::size_t k = 1;
      while (k < token.size() && is_digit(token[k])) ++k;
      if ((token[0] == 'T' || token[0] == 'B') && k < token.size() && token[k] == ':') r.has_temperature = true;
      continue;
    }
    long long v = -1;
    auto res = std::from_chars(token.data() + 1, token.data() + token.size(), v);
    if (res.ec != std::errc() || res.ptr != token.data() + token.size()) continue;
    if (token[0] == 'N') r.line = v;
    if (token[0] == 'P') r.planner_free = static_cast<int>(v);
    if (token[0] == 'B') r.queue_free = static_cast<int>(v);
  }
}

// The value of FIRMWARE_NAME: up to the next " KEY:" (SOURCE_CODE_URL:,
// FIRMWARE_URL:, FIRMWARE_VERSION:), blanks around it gone (RepRapFirmware
// writes "FIRMWARE_NAME: RepRapFirmware for Duet 3 ...").
std::string_view firmware_name(std::string_view rest) {
  rest = trim_noise(rest);
  for (std::size_t i = rest.find(' '); i != std::string_view::npos; i = rest.find(' ', i + 1)) {
    std::size_t k = i + 1;
    while (k < rest.size() && ((rest[k] >= 'A' && rest[k] <= 'Z') || rest[k] == '_')) ++k;
    if (k > i + 1 && k < rest.size() && rest[k] == ':') return trim_noise(rest.substr(0, i));
  }
  return rest;
}

}  // namespace

std::uint8_t checksum(std::string_view text) {
  std::uint8_t cs = 0;
  for (char c : text) cs ^= static_cast<std::uint8_t>(c);
  return cs;
}

void append_numbered_line(std::string& out, long long number, std::string_view command) {
  std::size_t start = out.size();
  char buf[24];
  out += 'N';
  auto res = std::to_chars(buf, buf + sizeof buf, number);
  out.append(buf, res.ptr);
  out += ' ';
  out += command;
  std::uint8_t cs = checksum(std::string_view(out).substr(start));
  out += '*';
  res = std::to_chars(buf, buf + sizeof buf, static_cast<unsigned>(cs));
  out.append(buf, res.ptr);
  out += '\n';
}

std::string_view command_of_numbered(std::string_view wire) {
  std::size_t space = wire.find(' ');
  std::size_t star = wire.rfind('*');
  return wire.substr(space + 1, star - space - 1);
}

ErrorClass classify_error(std::string_view m) {
  // Marlin: "checksum mismatch, Last Line: 5", "Line Number is not Last Line
  // Number+1, Last Line: 5", "No Checksum with line number, Last Line: 5",
  // "No Line Number with checksum, Last Line: 5"; Repetier: "expected line",
  // "Format error". Each is followed by a Resend request.
  if (contains_nocase(m, "checksum") || contains_nocase(m, "line number") || contains_nocase(m, "last line") ||
      contains_nocase(m, "expected line") || contains_nocase(m, "format error"))
    return ErrorClass::Resend;
  // Marlin's kill(): "Printer halted. kill() called!", "Printer stopped due to
  // errors. ... M999"; thermal protection: "Thermal Runaway", "MAXTEMP",
  // "MINTEMP", "Heating failed". Klipper: "Shutdown", "MCU ... shutdown".
  // RepRapFirmware: "Heater 1 fault: ...".
  if (contains_nocase(m, "halted") || contains_nocase(m, "kill()") || contains_nocase(m, "killed") ||
      contains_nocase(m, "stopped") || contains_nocase(m, "thermal runaway") || contains_nocase(m, "maxtemp") ||
      contains_nocase(m, "mintemp") || contains_nocase(m, "heating failed") || contains_nocase(m, "shutdown") ||
      contains_nocase(m, "emergency") || (contains_nocase(m, "heater") && contains_nocase(m, "fault")))
    return ErrorClass::Fatal;
  return ErrorClass::Recoverable;
}

bool says_not_homed(std::string_view message) {
  std::string_view m = trim_noise(message);
  if (contains_nocase(m, "must home") || contains_nocase(m, "axes homed")) return true;
  return starts_with_nocase(m, "home ") && contains_nocase(m, " first");
}

bool says_homing_failed(std::string_view message) {
  return contains_nocase(message, "no trigger on") || contains_nocase(message, "still triggered") ||
         contains_nocase(message, "triggered prior to movement") || contains_nocase(message, "homing failed");
}

bool is_reset_note(std::string_view text) {
  static constexpr std::string_view kNotes[] = {"External Reset", "Watchdog Reset", "Brown out Reset",
                                                "Software Reset", "Power-up"};
  for (std::string_view note : kNotes)
    if (contains_nocase(text, note)) return true;
  return false;
}

bool is_restart_line(std::string_view line) {
  Response r = parse_response(line);
  return r.kind == ResponseKind::Start || (r.kind == ResponseKind::Echo && is_reset_note(r.text));
}

Response parse_response(std::string_view raw) {
  Response r;
  // A board coming up may send a NUL before its greeting.
  while (!raw.empty() && raw.front() == '\0') raw.remove_prefix(1);
  std::string_view s = trim_noise(raw);
  r.text = s;
  if (s.empty()) return r;
  if (cut_by_greeting(s)) {
    r.kind = ResponseKind::Start;
    r.text = s.substr(s.size() - kGreeting.size());
    return r;
  }

  if (starts_with_nocase(s, "ok") && (s.size() == 2 || s[2] == ' ' || s[2] == ':' || is_digit(s[2]))) {
    r.kind = ResponseKind::Ok;
    r.text = s.substr(2);
    parse_ok_fields(r.text, r);
    return r;
  }
  // "Resend: 12", "Resend:12", "resend 12", "rs 12", "rs:12", "rs N12".
  if (starts_with_nocase(s, "resend") || (starts_with_nocase(s, "rs") && s.size() > 2 && (s[2] == ' ' || s[2] == ':'))) {
    long long n = first_integer(s);
    if (n >= 0) {
      r.kind = ResponseKind::Resend;
      r.line = n;
      return r;
    }
  }
  if (starts_with_nocase(s, "error:") || starts_with_nocase(s, "!!")) {
    r.kind = ResponseKind::Error;
    r.text = trim_noise(s.substr(s[0] == '!' ? 2 : 6));
    r.error = classify_error(r.text);
    return r;
  }
  std::string_view body = s;
  if (starts_with_nocase(body, "echo:")) body = trim_noise(body.substr(5));
  if (starts_with_nocase(body, "busy:")) {
    r.kind = ResponseKind::Busy;
    r.text = trim_noise(body.substr(5));
    return r;
  }
  // Marlin's "//action:pause", Prusa's "// action:paused".
  if (starts_with_nocase(s, "//") && starts_with_nocase(trim_noise(s.substr(2)), "action:")) {
    r.kind = ResponseKind::Action;
    r.text = trim_noise(trim_noise(s.substr(2)).substr(7));
    return r;
  }
  if (body.data() != s.data() || starts_with_nocase(s, "//")) {
    r.kind = ResponseKind::Echo;
    r.text = body.data() != s.data() ? body : trim_noise(s.substr(2));
    // Marlin's 'echo:Unknown command: "M123"', Klipper's '// Unknown command:"M123"'.
    r.unknown_command = starts_with_nocase(r.text, "unknown command");
    if (r.unknown_command) {
      std::size_t quote = r.text.find('"');
      r.lost_number = quote != std::string_view::npos && quote + 1 < r.text.size() && is_digit(r.text[quote + 1]);
      r.unknown_command = !r.lost_number;
    }
    // A fatal condition may also arrive as an echo on some firmware versions,
    // and Klipper announces its shutdown so ("// Klipper state: Shutdown").
    if (contains_nocase(r.text, "kill()") || contains_nocase(r.text, "printer halted") ||
        contains_nocase(r.text, "state: shutdown")) {
      r.kind = ResponseKind::Error;
      r.error = ErrorClass::Fatal;
    }
    return r;
  }
  if (starts_with_nocase(s, "T:") || starts_with_nocase(s, "B:") || (s.size() > 3 && s[0] == 'T' && is_digit(s[1]) && s[2] == ':')) {
    r.kind = ResponseKind::Temperature;
    return r;
  }
  if (s == "wait") {
    r.kind = ResponseKind::Wait;
    return r;
  }
  if (starts_with_nocase(s, "start")) {
    r.kind = ResponseKind::Start;
    return r;
  }
  if (starts_with_nocase(s, "Cap:") || starts_with_nocase(s, "FIRMWARE_NAME:")) {
    r.kind = ResponseKind::Capability;
    return r;
  }
  r.kind = ResponseKind::Unknown;
  if (contains_nocase(s, "kill()") || contains_nocase(s, "printer halted")) {
    r.kind = ResponseKind::Error;
    r.error = ErrorClass::Fatal;
  }
  return r;
}

std::string_view command_for_sending(std::string_view code) {
  std::string_view s = trim_command(code);
  if (!s.empty() && (s[0] == 'N' || s[0] == 'n') && s.size() > 1 && (is_digit(s[1]) || s[1] == '-')) {
    std::size_t i = 1;
    if (s[i] == '-') ++i;
    while (i < s.size() && is_digit(s[i])) ++i;
    s = trim_command(s.substr(i));
  }
  std::size_t star = s.rfind('*');
  if (star != std::string_view::npos) {
    bool digits = star + 1 < s.size();
    for (std::size_t i = star + 1; i < s.size(); ++i) digits = digits && is_digit(s[i]);
    if (digits) s = trim_command(s.substr(0, star));
  }
  return s;
}

std::string_view command_for_sending(const Line& line, std::string& scratch) {
  // Free text (M117 messages, macros) is the user's, parentheses and all.
  if (line.text.find('(') == std::string_view::npos || !line.argument.empty()) return command_for_sending(line.code());
  // Paren comments end at the first ')', a ';' inside them included (an
  // unclosed one at the end), as Line reads them; a ';' outside ends the code.
  scratch.clear();
  bool inside = false;
  for (char c : line.text) {
    if (inside) {
      inside = c != ')';
    } else if (c == ';') {
      break;
    } else if (c == '(') {
      inside = true;
      if (!scratch.empty() && scratch.back() != ' ') scratch.push_back(' ');
    } else if (c != ' ' || (!scratch.empty() && scratch.back() != ' ')) {
      scratch.push_back(c);
    }
  }
  return command_for_sending(scratch);
}

CapabilityLine read_capability(std::string_view text, FirmwareInfo& info) {
  CapabilityLine said;
  auto cap = [&](std::string_view name) {
    std::string key = "Cap:" + std::string(name) + ":1";
    return text.find(key) != std::string_view::npos;
  };
  // Klipper answers on its ok line: "ok FIRMWARE_NAME:Klipper FIRMWARE_VERSION:...".
  text = trim_noise(text);
  if (text.rfind("ok ", 0) == 0) text = trim_noise(text.substr(3));
  if (text.rfind("FIRMWARE_NAME:", 0) == 0) {
    said.names_firmware = true;
    info.name = std::string(firmware_name(text.substr(14)));
    auto number_after = [&](std::string_view key) {
      std::size_t p = text.find(key);
      if (p == std::string_view::npos) return 0.0;
      return std::atof(std::string(text.substr(p + key.size(), 24)).c_str());
    };
    info.time_scale = number_after("TIME_SCALE:");
    info.baud = number_after("BAUD:");
  }
  constexpr std::string_view kMaxCmd = "Cap:MAX_CMD_SIZE:";
  if (text.rfind(kMaxCmd, 0) == 0) {
    long long size = std::atoll(std::string(text.substr(kMaxCmd.size(), 12)).c_str());
    if (size >= 16) {
      info.max_line = static_cast<std::size_t>(size);
      said.max_line = true;
    }
  }
  if (cap("ADVANCED_OK")) info.advanced_ok = true;
  if (cap("EMERGENCY_PARSER")) info.emergency_parser = true;
  if (cap("AUTOREPORT_TEMP")) info.autoreport_temp = true;
  if (cap("BUSY_PROTOCOL") || cap("HOST_ACTION_COMMANDS")) info.busy_protocol = true;
  return said;
}

}  // namespace gcode::serial
