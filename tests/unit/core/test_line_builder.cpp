#include <catch2/catch.hpp>

#include "gcode/core/line.hpp"
#include "gcode/core/line_builder.hpp"

TEST_CASE("LineBuilder writes shortest numbers and keeps the comment", "[line_builder]") {
  gcode::LineBuilder b;
  b.start("G1").word('X', 10.5, 3).word('Y', 3.0, 3).word('E', 0.123456, 5).comment("; wall");
  CHECK(b.view() == "G1 X10.5 Y3 E0.12346 ; wall");
  b.start("G92").raw_word('E', "-.8");
  CHECK(b.view() == "G92 E-.8");
  gcode::Line back = gcode::Line::parse(b.view());
  CHECK(back.find('E')->value() == -0.8);
}

TEST_CASE("Precision keeps at least the input's decimals", "[line_builder]") {
  gcode::Precision p;
  CHECK(p.of('X') == 3);
  CHECK(p.of('E') == 5);
  CHECK(p.of('F') == 0);
  p.observe_word('X', "1.23456");
  p.observe_word('E', "1.2");
  p.observe_word('F', "7800.000");
  CHECK(p.of('X') == 5);
  CHECK(p.of('E') == 5);
  CHECK(p.of('F') == 3);
  p.observe_word('Z', "1.12345678901");
  CHECK(p.of('Z') == 9);
}
