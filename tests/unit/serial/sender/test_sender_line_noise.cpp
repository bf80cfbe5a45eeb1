// Line noise and the lines gc-send writes on its own (issue 41): a pace
// probe (a move of no length) and a question (M105), as the sender writes
// them while printing, with every byte changed by one bit, by two bits, and
// two bytes by one bit each (bits that differ: the same bit in two bytes is
// what an XOR checksum cannot see, for any line). Marlin, as the virtual
// printer models it, checks the number and checksum of a numbered line and
// runs an unnumbered one as it comes: whatever the noise made of the line,
// the printer ran it as it was written or refused it, never as another
// command (an unnumbered "G1" with one bit changed is "G0" or "G3"; with
// two, "M1": a wait for the user).
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/serial/protocol/protocol.hpp"
#include "gcode/serial/sender/sender.hpp"
#include "gcode/serial/sim/virtual_printer.hpp"
#include "serial_check.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

namespace line_noise_test {

struct OwnLines {
  std::string probe;     // the first pace probe written, with its newline
  std::string question;  // the first M105 written
};

// The command of a line as written ("N12 G1*86" -> "G1").
std::string command_of(std::string_view line) {
  if (!line.empty() && line.front() == 'N') return std::string(command_of_numbered(line));
  return std::string(command_for_sending(line));
}

// A paced print on a Marlin whose oks get lost: the sender asks with pace
// probes (its planner full) and with M105 (an answer overdue). Returns the
// first of each it writes.
OwnLines own_lines_written() {
  std::vector<std::string> commands;
  for (auto& c : gctest::commands_of(gctest::read_file(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")),
                                     3000))
    commands.push_back(c.text);
  VirtualPrinterConfig pc;
  pc.heat_rate = 1000;
  pc.drop_ok = 0.02;
  VirtualPrinter printer(pc);
  SenderConfig sc;
  sc.pace = true;
  sc.read_ahead = 1;
  sc.link_bytes_per_second = pc.baud / 10;
  Sender sender(sc, nullptr);
  OwnLines own;
  std::string rx, written;
  std::size_t next = 0;
  double t = 0;
  sender.start(t);
  while (!sender.finished() && t < 1e5 && (own.probe.empty() || own.question.empty())) {
    while (sender.wants_input() && next < commands.size()) {
      sender.submit(commands[next], next + 1, 1);
      ++next;
    }
    if (next == commands.size()) sender.end_of_input();
    sender.pump(t);
    std::string_view out = sender.output();
    printer.receive(out, t);
    written.append(out);
    sender.written(out.size(), t);
    for (std::size_t nl; (nl = written.find('\n')) != std::string::npos; written.erase(0, nl + 1)) {
      std::string line = written.substr(0, nl + 1);
      std::string command = command_of(line.substr(0, nl));
      if (command == "G1" && own.probe.empty()) own.probe = line;
      if (command == "M105" && own.question.empty()) own.question = line;
    }
    printer.advance(t);
    std::string_view tx = printer.transmitted(t);
    rx.append(tx);
    printer.take(tx.size());
    for (std::size_t nl; (nl = rx.find('\n')) != std::string::npos; rx.erase(0, nl + 1))
      sender.on_line(std::string_view(rx).substr(0, nl), t);
    if (!sender.output().empty()) continue;
    if (sender.deadline() <= t) sender.on_timer(t);
    if (!sender.output().empty() || (sender.wants_input() && next < commands.size())) continue;
    double next_t = std::min(printer.next_event(), sender.deadline());
    t = next_t <= t ? t + 1e-6 : next_t;
  }
  return own;
}

// What a fresh Marlin that expects the line's number runs of `bytes`: the
// commands of its executed log, after the M110 that set the number.
std::vector<std::string> ran(const std::string& original, const std::string& bytes) {
  char* buffer = nullptr;
  std::size_t size = 0;
  std::FILE* log = open_memstream(&buffer, &size);
  const long long n = original.front() == 'N' ? std::strtoll(original.c_str() + 1, nullptr, 10) : 1;
  const std::string set_number = "M110 N" + std::to_string(n - 1);
  {
    VirtualPrinter printer(VirtualPrinterConfig{}, log);
    printer.receive(set_number + "\n", 0);
    printer.advance(0.01);
    printer.receive(bytes + "\n", 0.01);  // (a newline the noise took ends the line all the same)
    printer.advance(1);
  }
  std::fclose(log);
  std::string text(buffer, size);
  std::free(buffer);
  // Rows: time, N (-1: unnumbered), X, Y, Z, E, the command.
  std::vector<std::string> out;
  for (std::size_t start = 0, end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
    std::string_view row = std::string_view(text).substr(start, end - start);
    std::size_t c = 0;
    for (int i = 0; i < 6; ++i) c = row.find('\t', c) + 1;
    std::string command(row.substr(c));
    if (command != set_number) out.push_back(command);
  }
  return out;
}

// The same command, and for a move one that moves nothing and changes no
// feed rate: "n48 G1.20" and "n48 G1j20" (the N and the '*' hit, so the
// line lost its number and its check) are a G1 with a subcode or a J word
// that a move of no length ignores.
bool same_command(const gcode::Line& ran, const gcode::Line& written) {
  if (ran.kind != written.kind || ran.letter != written.letter || ran.number != written.number) return false;
  if (!ran.is_move()) return true;
  for (char axis : {'X', 'Y', 'Z', 'E', 'F', 'A', 'B', 'C', 'U', 'V', 'W'})
    if (ran.has(axis)) return false;
  return true;
}

// Whether what ran is only the line as written: a G, M or T command other
// than it is the harm (Marlin answers a fragment without one, "O48 G1(20"
// or "86", as an unknown command and does nothing).
void check_noise(const std::string& line, std::size_t i, std::size_t j, unsigned mask_i, unsigned mask_j) {
  std::string bytes = line.substr(0, line.size() - 1);
  bytes[i] = static_cast<char>(static_cast<unsigned char>(bytes[i]) ^ mask_i);
  if (mask_j != 0) bytes[j] = static_cast<char>(static_cast<unsigned char>(bytes[j]) ^ mask_j);
  const std::string want = command_of(line.substr(0, line.size() - 1));
  for (const std::string& c : ran(line, bytes)) {
    gcode::Line parsed = gcode::Line::parse(c);
    const bool command = (parsed.kind == gcode::CommandKind::Standard &&
                          (parsed.letter == 'G' || parsed.letter == 'M' || parsed.letter == 'T')) ||
                         parsed.kind == gcode::CommandKind::Extended;
    if (!command) continue;
    INFO("written " << line.substr(0, line.size() - 1) << ", arrived " << bytes << ", ran " << c);
    REQUIRE(same_command(parsed, gcode::Line::parse(want)));
  }
}

void check_every_error(const std::string& line) {
  REQUIRE(line.size() > 1);
  const std::size_t n = line.size() - 1;  // the newline is the link's, not the line's
  for (std::size_t i = 0; i < n; ++i) {
    for (unsigned a = 0; a < 8; ++a) {
      check_noise(line, i, i, 1u << a, 0);
      for (unsigned b = a + 1; b < 8; ++b) check_noise(line, i, i, (1u << a) | (1u << b), 0);
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (unsigned a = 0; a < 8; ++a)
        for (unsigned b = 0; b < 8; ++b)
          if (a != b) check_noise(line, i, j, 1u << a, 1u << b);
}

}  // namespace line_noise_test

TEST_CASE("line noise: a pace probe and an M105 the sender writes never run as another command",
          "[serial][noise]") {
  line_noise_test::OwnLines own = line_noise_test::own_lines_written();
  INFO("probe " << own.probe << "question " << own.question);
  REQUIRE_FALSE(own.probe.empty());
  REQUIRE_FALSE(own.question.empty());
  // Numbered and checksummed, as every line while printing.
  CHECK(own.probe.front() == 'N');
  CHECK(own.question.front() == 'N');
  line_noise_test::check_every_error(own.probe);
  line_noise_test::check_every_error(own.question);
}
