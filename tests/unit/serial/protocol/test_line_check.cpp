// What may go to the firmware (gcode/serial/protocol/line_check.hpp): lines that fit
// Marlin's MAX_CMD_SIZE with their number and checksum, messages cut to fit,
// and refusals for over-long lines and bytes the firmware cannot read.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/serial/protocol/line_check.hpp"
#include "gcode/serial/protocol/protocol.hpp"

using namespace gcode::serial;

namespace {

std::size_t wire_length(long long number, std::string_view command) {
  std::string s;
  append_numbered_line(s, number, command);
  return s.size() - 1;  // without the newline
}

}  // namespace

TEST_CASE("line check: numbered_length is the numbered line's size without the newline", "[serial]") {
  for (long long n : {1LL, 9LL, 10LL, 99999LL, 1234567LL})
    for (std::string_view c : {"G1 X1", "M117 Hello", "G28", "M105", "G1 X10.123 Y20.456 E0.01234"}) {
      INFO(n << " " << c);
      CHECK(numbered_length(n, c) == wire_length(n, c));
    }
}

TEST_CASE("line check: a line that fits is sent unchanged up to exactly max_line - 1 bytes", "[serial]") {
  std::string g1 = "G1 X10.123 Y20.456 E0.01234";
  LineCheck ok = check_line(g1, 12, 96);
  CHECK(ok.problem == LineProblem::None);
  CHECK(ok.command == g1);
  CHECK(ok.length == wire_length(12, g1));
  // Commands whose numbered form is exactly 95 and 96 bytes (the checksum's
  // width varies, so try a few fillers).
  std::string fits, text;
  for (std::size_t n = 70; n < 90; ++n)
    for (const char* end : {"", "5"}) {
      std::string t = "G1 X1" + std::string(n, '0') + end;
      if (wire_length(7, t) == 95 && fits.empty()) fits = t;
      if (wire_length(7, t) == 96 && text.empty()) text = t;
    }
  REQUIRE(wire_length(7, fits) == 95);
  CHECK(check_line(fits, 7, 96).problem == LineProblem::None);
  REQUIRE(wire_length(7, text) == 96);
  LineCheck too_long = check_line(text, 7, 96);
  CHECK(too_long.problem == LineProblem::TooLong);
  CHECK(too_long.command.empty());
  CHECK(too_long.length == 96);
  CHECK(describe(too_long, 96) ==
        "the line is 96 bytes with its line number and checksum; the printer keeps 95 (--max-line 96) and would refuse "
        "it every time it is sent");
  // A larger buffer takes it.
  CHECK(check_line(text, 7, 200).problem == LineProblem::None);
}

TEST_CASE("line check: a 155-character M117 is cut to fit with its line number and checksum", "[serial]") {
  std::string message = "M117 " + std::string(150, 'x');
  for (long long n : {1LL, 42LL, 123456LL}) {
    LineCheck c = check_line(message, n, 96);
    INFO(n);
    CHECK(c.problem == LineProblem::Shortened);
    CHECK(c.length == wire_length(n, message));
    CHECK(message.rfind(c.command, 0) == 0);  // a prefix
    CHECK(wire_length(n, c.command) <= 95);
    // The widest checksum (3 digits) is assumed, so at most 2 bytes are lost to it.
    CHECK(wire_length(n, c.command) >= 93);
  }
  LineCheck c = check_line(message, 42, 96);
  // "N42 " + text + "*" + 3 digits = 95: 87 bytes of command.
  CHECK(c.command.size() == 87);
  CHECK(describe(c, 96) ==
        "M117 message shortened to 87 bytes: the printer keeps 95 bytes of a line (--max-line 96), this one would be "
        "162 with its line number and checksum");
  CHECK(check_line("M118 E1 " + std::string(200, 'y'), 5, 96).problem == LineProblem::Shortened);
  // M1170 is not a message.
  CHECK(check_line("M1170 " + std::string(200, 'y'), 5, 96).problem == LineProblem::TooLong);
}

TEST_CASE("line check: a shortened message ends on a whole UTF-8 character and no blank", "[serial]") {
  std::string text = "M117 ";
  for (int i = 0; i < 60; ++i) text += "\xC3\xA9 ";  // "é "
  LineCheck c = check_line(text, 3, 60);
  REQUIRE(c.problem == LineProblem::Shortened);
  CHECK(c.command.back() == '\xA9');
  CHECK(wire_length(3, c.command) <= 59);
  std::string spaced = "M117 " + std::string(40, 'a') + std::string(40, ' ') + "b";
  LineCheck d = check_line(spaced, 3, 60);
  REQUIRE(d.problem == LineProblem::Shortened);
  CHECK(d.command == "M117 " + std::string(40, 'a'));
}

TEST_CASE("line check: control bytes and binary junk are refused with their column", "[serial]") {
  LineCheck nul = check_line(std::string("G1 X1\0Y2", 8), 1, 96);
  CHECK(nul.problem == LineProblem::Unreadable);
  CHECK(nul.column == 6);
  CHECK(nul.byte == 0);
  CHECK(nul.command.empty());
  CHECK(describe(nul, 96) == "byte 0x00 at column 6 is not G-code text (a control byte or binary data)");
  CHECK(check_line("G1 X1\rY2", 1, 96).column == 6);       // CR ends a line in Marlin
  CHECK(check_line("G1 X1\x08Y2", 1, 96).byte == 0x08);    // backspace erases
  CHECK(check_line("G1 X1\x7FY2", 1, 96).byte == 0x7F);
  CHECK(check_line("\x1B[2J", 1, 96).column == 1);
  LineCheck junk = check_line("G1 \xFF\xFE\x89PNG", 1, 96);
  CHECK(junk.problem == LineProblem::Unreadable);
  CHECK(junk.column == 4);
  CHECK(junk.byte == 0xFF);
  // Overlong and surrogate encodings are not text either.
  CHECK(check_line("M117 \xC0\xAF", 1, 96).problem == LineProblem::Unreadable);
  CHECK(check_line("M117 \xED\xA0\x80", 1, 96).problem == LineProblem::Unreadable);
  CHECK(check_line("M117 \xE2\x82", 1, 96).problem == LineProblem::Unreadable);  // cut short
  LineCheck backslash = check_line("M117 C:\\prints", 1, 96);
  CHECK(backslash.problem == LineProblem::Unreadable);
  CHECK(backslash.column == 8);
  CHECK(describe(backslash, 96) ==
        "a backslash at column 8: Marlin reads it as an escape, so the line would never match its checksum");
  // Tabs and UTF-8 text (an LCD message) are fine.
  CHECK(check_line("G1\tX1", 1, 96).problem == LineProblem::None);
  CHECK(check_line("M117 Temp\xC3\xA9rature \xE2\x9C\x93 \xF0\x9F\x96\xA8", 1, 96).problem == LineProblem::None);
  // Unreadable is reported before too long.
  CHECK(check_line(std::string(200, 'G') + "\x01", 1, 96).problem == LineProblem::Unreadable);
}
