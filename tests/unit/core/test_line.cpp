#include <catch2/catch.hpp>

#include <random>

#include "gcode/core/line.hpp"

using gcode::CommandKind;
using gcode::Line;

TEST_CASE("a plain move", "[line]") {
  Line l = Line::parse("G1 X10.5 Y-3 E.12345 F1800 ; perimeter");
  CHECK(l.kind == CommandKind::Standard);
  CHECK(l.is_g(1));
  CHECK(l.is_move());
  REQUIRE(l.word_count() == 4);
  CHECK(l.find('X')->value() == 10.5);
  CHECK(l.find('Y')->value() == -3);
  CHECK(l.find('E')->raw == ".12345");
  CHECK(l.find('F')->value() == 1800);
  CHECK(l.comment == "; perimeter");
  CHECK(l.comment_text() == "perimeter");
  CHECK(l.code() == "G1 X10.5 Y-3 E.12345 F1800");
  CHECK_FALSE(l.malformed);
}

TEST_CASE("what Marlin accepts: packed, lower case, +, spaces, missing zero", "[line]") {
  Line l = Line::parse("g1x10Y5E.5");
  CHECK(l.is_g(1));
  CHECK(l.find('X')->value() == 10);
  CHECK(l.find('Y')->value() == 5);
  CHECK(l.find('E')->value() == 0.5);
  Line s = Line::parse("G1 X +10 Y -2");
  CHECK(s.find('X')->value() == 10);
  CHECK(s.find('Y')->value() == -2);
  Line e = Line::parse("G1X5E2");  // upper-case E is a word, not an exponent
  CHECK(e.find('X')->value() == 5);
  CHECK(e.find('E')->value() == 2);
}

TEST_CASE("line numbers, checksums and subcodes", "[line]") {
  Line l = Line::parse("N123 G1 X1*71");
  CHECK(l.has_line_number);
  CHECK(l.line_number == 123);
  CHECK(l.has_checksum);
  CHECK(l.checksum == 71);
  CHECK(l.find('X')->value() == 1);
  Line s = Line::parse("G29.1 Z0.2");
  CHECK(s.number == 29);
  CHECK(s.subcode == 1);
  CHECK_FALSE(s.is_g(29) == false);
}

TEST_CASE("words without numbers and string arguments", "[line]") {
  Line h = Line::parse("G28 X Y");
  REQUIRE(h.word_count() == 2);
  CHECK_FALSE(h.find('X')->has_value);
  Line m = Line::parse("M117 Printing X1.5 layer 3; note");
  CHECK(m.word_count() == 0);
  CHECK(m.argument == "Printing X1.5 layer 3");
  CHECK(m.comment == "; note");
}

TEST_CASE("host commands, macros, comments", "[line]") {
  CHECK(Line::parse("@pause now").kind == CommandKind::Host);
  CHECK(Line::parse("@pause now").command == "@pause");
  Line k = Line::parse("PRINT_START EXTRUDER=210 BED=60");
  CHECK(k.kind == CommandKind::Extended);
  CHECK(k.command == "PRINT_START");
  CHECK(k.argument == "EXTRUDER=210 BED=60");
  Line c = Line::parse(";LAYER:3");
  CHECK(c.kind == CommandKind::None);
  CHECK(c.comment_text() == "LAYER:3");
  Line p = Line::parse("G1 X1 (inline) Y2");
  CHECK(p.find('Y')->value() == 2);
  CHECK(p.comment == "(inline)");
  // A line of "(...)" comments only is a comment line, not junk.
  for (const char* text : {"(layer 2)", "  (a) (b) ; c", "(T0 PLA)"}) {
    Line only = Line::parse(text);
    INFO(text);
    CHECK_FALSE(only.malformed);
    CHECK(only.kind == CommandKind::None);
    CHECK_FALSE(only.is_blank());
    CHECK(only.code().empty());
  }
  CHECK(Line::parse("(layer 2)").comment_text() == "layer 2");
  CHECK(Line::parse("(a (b) c)").malformed);  // they do not nest
  CHECK(Line::parse("(unclosed").malformed);
  CHECK(Line::parse("").is_blank());
  CHECK(Line::parse("   \t").is_blank());
}

TEST_CASE("malformed lines are flagged, never thrown", "[line]") {
  CHECK(Line::parse("G1 X1e309").malformed);
  CHECK(Line::parse("G1 Xnan Y1").malformed);
  CHECK(Line::parse("G1 X1.2.3").malformed);
  CHECK(Line::parse("\x01\x02\xff junk").malformed);
  CHECK(Line::parse("G1 X{foo}").malformed);
  std::string many = "G1";
  for (int i = 0; i < 40; ++i) many += " X1";
  CHECK(Line::parse(many).malformed);
  std::string huge(10 << 20, 'A');
  CHECK_NOTHROW(Line::parse(huge));
}

TEST_CASE("a slicer's move line through the fast path: every field as the full scan gives it", "[line]") {
  Line l = Line::parse("G1 X114.275 Y-96.8 E.18786 ; perimeter");
  CHECK(l.kind == CommandKind::Standard);
  CHECK(l.is_g(1));
  CHECK(l.subcode == -1);
  CHECK(l.command == "G1");
  CHECK_FALSE(l.malformed);
  REQUIRE(l.word_count() == 3);
  CHECK(l.word(0).raw == "114.275");
  CHECK(l.word(0).mantissa == 114275);
  CHECK(l.word(0).decimals == 3);
  CHECK(l.word(1).mantissa == -968);
  CHECK(l.word(2).value() == 0.18786);
  CHECK(l.comment == "; perimeter");
  CHECK(l.comment_pos == 27);
}

TEST_CASE("words know how many decimals they were written with", "[line]") {
  Line l = Line::parse("G1 X10 Y-.80 Z1.125 E1e-3 F7800.000");
  CHECK(l.find('X')->decimals == 0);
  CHECK(l.find('Y')->decimals == 2);
  CHECK(l.find('Z')->decimals == 3);
  CHECK(l.find('F')->decimals == 3);
}

#include "reference_line.hpp"
#include "test_support.hpp"

TEST_CASE("the single-pass parser reads every fixture line as the reference parser does", "[line][property]") {
  std::size_t lines = 0;
  for (const std::string& name : gctest::fixture_names()) {
    std::string text = gctest::read_file(gctest::fixture_path(name));
    gcode::MemoryLineSplitter split(text);
    gcode::RawLine raw;
    while (split.next(raw)) {
      ++lines;
      std::string diff = gctest::compare_with_reference(Line::parse(raw.text), gctest::reference_parse(raw.text));
      if (!diff.empty()) FAIL(name << ":" << raw.number << ": '" << raw.text << "' differs in " << diff);
    }
  }
  CHECK(lines > 100000);
}

TEST_CASE("the single-pass parser agrees with the reference on odd lines", "[line][property]") {
  const char* odd[] = {"N12*34", "N12 *34 G1", "N12 ;c", "G1 X1*71 ; c", "G1 X1.*71", "G*12", "G ;c", "G",
                       "AB*12", "@pause now ; c", "@", "X*12", "A;", "G1 X1 (abc*12", "G1 X1 (a;b) Y2",
                       "G1 (x) (y) Z3", "M117 hi*45", "N3 M117 a ; b", "G1 X1 *999", "G1 X1 * 12", "G29.1 Z.2",
                       "g1x1y2e.5f300", "G1 X-.5 Y+3 E1e3", "G1 X1e309", "G1 X 1 Y\t2", "\x01\x02\xff junk",
                       "G1\rX1", "T0", "M104 S210 T1 ; heat", "G92 E0.0", "G1 X12345678901234567890 Y1",
                       "G1 X0.1234567890123 Y1", "  ;  comment only", "", "   ", "G1 X1 Y2 ;; x ; y", "(only)",
                       "G1 X1 )", "G1 X1 *12 ;c", "N1 G1 X2*99 (x)", "(a) (b) ; c", "(a ; b) c", "(a)*12",
                       "(a (b) c)", "(unclosed", " (x)\t", "(a) G1 X1",
                       // The move fast path's edges (each falls back or agrees).
                       "G1 X5.", "G1 X-0", "G1 X.", "G1 X-", "G1 X5;c", "G1 X5*12", "G1 X5 *12", "G1 XY5", "G1 X5\t",
                       "G1 X1.2.3", "G1 x5", "G1  X5  ", "G0", "G3 X1 Y2 I3 J4 E.5", "G1 X000000000000000001",
                       "G1 X0000000000000000001", "G1 X5 N3", "G1 X\x8c", "G1;c", "G10 X1",
                       // Subcodes and line numbers too long for an int: capped, not overflowed.
                       "G1.222222222222", "G1.2222222222222222222 X1", "N99999999999999999999999 G1 X1",
                       "N121  G\x8c",
                       // Digit runs of 7 to 19, at the line's end, before bytes next to the digits or above 0x7f.
                       "G1 X1234567", "G1 X12345678", "G1 X123456789 Y1", "G1 X.12345678", "G1 X1234567.12345678",
                       "G1 X123456789.123456789", "G1 X1234567890.12345678", "G1 X12\xb0 Y1", "G1 X1\x8a\x35 Y1",
                       "G1 X12/4", "G1 X12:4", "G1 Y9 X1234567890123456789", "G1 E.0214799"};
  for (const char* text : odd) {
    INFO("'" << text << "'");
    CHECK(gctest::compare_with_reference(Line::parse(text), gctest::reference_parse(text)) == "");
  }
}

TEST_CASE("the single-pass parser agrees with the reference on random move lines", "[line][property]") {
  // The move fast path's digit runs, blanks, points and signs in every order
  // and length, with bytes next to the digits ('/', ':') and above 0x7f.
  const std::string_view alphabet = "G1 XYEF.-0123456789;/:\x8a\xff";
  std::mt19937 random(25);
  std::size_t differ = 0;
  std::string first;
  for (int i = 0; i < 200000; ++i) {
    std::string text = i % 2 == 0 ? "G1 X" : "G0 ";
    const std::size_t length = random() % 40;
    for (std::size_t k = 0; k < length; ++k) {
      // Mostly digits, so runs of every length come up.
      const std::size_t pick = random() % 3 == 0 ? random() % alphabet.size() : 9 + random() % 10;
      text += alphabet[pick];
    }
    std::string diff = gctest::compare_with_reference(Line::parse(text), gctest::reference_parse(text));
    if (!diff.empty() && differ++ == 0) first = "'" + text + "' differs in " + diff;
  }
  INFO(first);
  CHECK(differ == 0);
}
