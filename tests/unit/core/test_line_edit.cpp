// line_edit.hpp: changed words in place, new words before the comment, the
// rest of the line byte for byte.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/core/line_edit.hpp"

using gcode::Fixed;
using gcode::Line;
using gcode::LineEdit;

namespace {
std::string edit(const std::string& text, void (*change)(LineEdit&)) {
  Line line = Line::parse(text);
  LineEdit e(line);
  change(e);
  return std::string(e.text());
}
}  // namespace

TEST_CASE("line edit replaces a value in place and keeps spacing and comment", "[line_edit]") {
  CHECK(edit("G1  X10.5 Y3\tF1800 ; outer wall", [](LineEdit& e) { e.set('F', "5400"); }) ==
        "G1  X10.5 Y3\tF5400 ; outer wall");
  CHECK(edit("g1x1y2f300", [](LineEdit& e) { e.set('F', Fixed::from_int(900), 0); }) == "g1x1y2f900");
  CHECK(edit("G1 X1 E.5", [](LineEdit& e) { e.set('E', Fixed::from_decimal(25, 2), 5); }) == "G1 X1 E0.25");
}

TEST_CASE("line edit appends a missing word before the comment", "[line_edit]") {
  CHECK(edit("G1 X10 Y5 ; c", [](LineEdit& e) { e.set('F', "1200"); }) == "G1 X10 Y5 F1200 ; c");
  CHECK(edit("G1 X10 Y5", [](LineEdit& e) { e.set('F', "1200"); }) == "G1 X10 Y5 F1200");
  CHECK(edit("G1 X10   ", [](LineEdit& e) { e.set('F', "1200"); }) == "G1 X10 F1200   ");
}

TEST_CASE("line edit removes words with their blanks", "[line_edit]") {
  CHECK(edit("G1 F300 X10 Y5 ; c", [](LineEdit& e) { e.remove('F'); }) == "G1 X10 Y5 ; c");
  CHECK(edit("G1 X10 Y5 F300", [](LineEdit& e) { e.remove('F'); }) == "G1 X10 Y5");
  CHECK(edit("G28 X Y", [](LineEdit& e) { e.remove('X'); }) == "G28 Y");
}

TEST_CASE("line edit adds a note after the comment", "[line_edit]") {
  CHECK(edit("G1 X1 F100 ; wall", [](LineEdit& e) { e.set('F', "300").note("gc-speedup x3"); }) ==
        "G1 X1 F300 ; wall ; gc-speedup x3");
  CHECK(edit("G1 X1", [](LineEdit& e) { e.note("mark"); }) == "G1 X1 ; mark");
}
