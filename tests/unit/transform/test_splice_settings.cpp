// CarriedSettings (transform/carried_settings.hpp): which lines set what a
// seam carries, and the lines that bring one printer's settings to another's.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/transform/carried_settings.hpp"

using gcode::CarriedSettings;
using Kind = CarriedSettings::Kind;

namespace {

CarriedSettings settings_of(const std::vector<std::string>& lines, int tool = 0) {
  CarriedSettings s;
  for (const std::string& l : lines) s.observe(gcode::Line::parse(l), tool);
  return s;
}

}  // namespace

TEST_CASE("splice settings: heaters fans flow and advance are recorded per slot", "[splice][settings]") {
  CarriedSettings s = settings_of({"M104 S200", "M109 S215 ; wait", "M104 T1 S190", "M140 S60", "M190 R55",
                                   "M106 S128", "M106 P1", "M221 S95", "M900 K0.04", "M572 D0 S0.06",
                                   "SET_PRESSURE_ADVANCE ADVANCE=0.05", "G10 P2 S180 R150", "M141 S40"});
  REQUIRE(s.find(Kind::Hotend, 0) != nullptr);
  CHECK(s.find(Kind::Hotend, 0)->value == gcode::Fixed::from_int(215));
  CHECK(s.find(Kind::Hotend, 0)->text == "M109 S215");  // the code, without its comment
  CHECK(s.find(Kind::Hotend, 1)->value == gcode::Fixed::from_int(190));
  CHECK(s.find(Kind::Hotend, 2)->text == "G10 P2 S180 R150");
  CHECK(s.find(Kind::Bed, 0)->value == gcode::Fixed::from_int(55));
  CHECK(s.find(Kind::Chamber, 0)->value == gcode::Fixed::from_int(40));
  CHECK(s.find(Kind::Fan, 0)->value == gcode::Fixed::from_int(128));
  CHECK(s.find(Kind::Fan, 1)->value == gcode::Fixed::from_int(255));  // M106 without S: full
  CHECK(s.find(Kind::Flow, 0)->value == gcode::Fixed::from_int(95));
  CHECK(s.find(Kind::Advance, 0, "M900")->text == "M900 K0.04");
  CHECK(s.find(Kind::Advance, 0, "M572")->text == "M572 D0 S0.06");
  CHECK(s.find(Kind::Advance, 0, "SET_PRESSURE_ADVANCE ")->text == "SET_PRESSURE_ADVANCE ADVANCE=0.05");
  CHECK(settings_of({"M106 S200", "M107"}).find(Kind::Fan, 0)->value.is_zero());
}

TEST_CASE("splice settings: other lines set nothing", "[splice][settings]") {
  for (const char* text : {"G1 X10 E1", "M105", "M221", "M900", "G10", "G10 P0", "M117 M104 S200", "; M104 S200",
                           "PRINT_START EXTRUDER=210", "M82", "T1"}) {
    INFO(text);
    CarriedSettings s;
    CHECK_FALSE(s.observe(gcode::Line::parse(text), 0));
    CHECK(s.empty());
  }
}

TEST_CASE("splice settings: lines from one set to another wait for heaters that rise", "[splice][settings]") {
  CarriedSettings printed = settings_of({"M140 S60", "M104 S215", "M106 S255", "M900 K0.04", "M221 S95"});
  CarriedSettings block = settings_of({"M140 S70", "M104 S220", "M106 S255", "M900 K0.06", "M221 S95"});
  CHECK(block.lines_from(printed, 0) == std::vector<std::string>{"M190 S70", "M109 S220", "M900 K0.06"});
  CHECK(printed.lines_from(block, 0) == std::vector<std::string>{"M140 S60", "M104 S215", "M900 K0.04"});
  CHECK(block.lines_from(block, 0).empty());
  // A slot the printed side never set is written; one the block never set is left alone.
  CarriedSettings bare;
  CHECK(block.lines_from(bare, 0).size() == 5);
  CHECK(bare.lines_from(block, 0).empty());
  // Another tool's heater names its tool.
  CHECK(settings_of({"M104 T1 S200"}).lines_from(bare, 0) == std::vector<std::string>{"M109 T1 S200"});
}

TEST_CASE("splice settings: equal sets compare equal whatever the order they were set in", "[splice][settings]") {
  CarriedSettings a = settings_of({"M104 S215", "M140 S60", "M106 S255"});
  CarriedSettings b = settings_of({"M106 S255", "M190 S60", "M109 S215"});
  CHECK(a == b);
  b.observe(gcode::Line::parse("M106 S254"), 0);
  CHECK_FALSE(a == b);
  CarriedSettings c = a;
  c.adopt(b);
  CHECK(c == b);
}
