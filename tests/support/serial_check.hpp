#pragma once
// Shared by the serial tests: what gc-send should send for a G-code text, and
// what the virtual printer's log says it executed.
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/serial/protocol/protocol.hpp"

namespace gctest {

struct SentCommand {
  std::string text;           // as sent: no comment, no N, no checksum
  std::uint64_t source_line;  // 1-based line in the text
};

// The commands of `text` gc-send sends, in order (comments, blank lines,
// host commands and M110 left out), at most `limit`.
inline std::vector<SentCommand> commands_of(std::string_view text, std::size_t limit = static_cast<std::size_t>(-1)) {
  std::vector<SentCommand> out;
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  std::string scratch;
  while (split.next(raw) && out.size() < limit) {
    gcode::Line line = gcode::Line::parse(raw.text);
    if (line.kind == gcode::CommandKind::None || line.kind == gcode::CommandKind::Host || line.is_m(110)) continue;
    // "(...)" comments inside the code are taken out, not cut at.
    std::string_view cmd = gcode::serial::command_for_sending(line, scratch);
    if (!cmd.empty()) out.push_back({std::string(cmd), raw.number});
  }
  return out;
}

struct ExecutedLog {
  std::vector<long long> numbers;     // line numbers of the numbered commands, in execution order
  std::vector<std::string> commands;  // their text
  std::size_t unnumbered = 0;         // handshake, M105 probes
  std::vector<std::string> notes;     // "#" lines: resets and link drops
};

// Reads the virtual printer's log: time, N, X, Y, Z, E, command (tab-separated),
// and its notes of resets and link drops ("# ...").
inline ExecutedLog parse_executed_log(std::string_view text) {
  ExecutedLog log;
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) {
    std::string_view s = raw.text;
    if (!s.empty() && s[0] == '#') {
      log.notes.emplace_back(s);
      continue;
    }
    std::size_t a = s.find('\t');
    std::size_t b = s.find('\t', a + 1);
    long long n = std::stoll(std::string(s.substr(a + 1, b - a - 1)));
    std::size_t c = b;
    for (int i = 0; i < 4; ++i) c = s.find('\t', c + 1);
    if (n < 0) {
      ++log.unnumbered;
      continue;
    }
    log.numbers.push_back(n);
    log.commands.emplace_back(s.substr(c + 1));
  }
  return log;
}

// gc-send's own lines (an M105 question, a bare G1 pace probe), numbered
// like the file's, taken out of `log` where `expected` (the commands of the
// input, in order) does not have them: what is left is the input's, in
// order, with numbers that only rise. Returns how many were taken out.
inline std::size_t drop_own_lines(ExecutedLog& log, const std::vector<std::string>& expected) {
  ExecutedLog kept;
  kept.unnumbered = log.unnumbered;
  kept.notes = log.notes;
  std::size_t j = 0, own = 0;
  for (std::size_t i = 0; i < log.commands.size(); ++i) {
    const std::string& c = log.commands[i];
    if (j < expected.size() && c == expected[j]) {
      ++j;
    } else if (c == "G1" || c == "M105") {
      ++own;
      continue;
    }
    kept.commands.push_back(c);
    kept.numbers.push_back(log.numbers[i]);
  }
  log = std::move(kept);
  return own;
}

inline std::size_t drop_own_lines(ExecutedLog& log, const std::vector<SentCommand>& expected) {
  std::vector<std::string> texts;
  for (const SentCommand& c : expected) texts.push_back(c.text);
  texts.emplace_back("M400");
  return drop_own_lines(log, texts);
}

// The numbers of what the printer executed only rise (each line once, in order).
inline bool numbers_rise(const std::vector<long long>& numbers) {
  for (std::size_t i = 1; i < numbers.size(); ++i)
    if (numbers[i] <= numbers[i - 1]) return false;
  return true;
}

}  // namespace gctest
