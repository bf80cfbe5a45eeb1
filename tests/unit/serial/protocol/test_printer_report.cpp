// What a printer says about where it is (gcode/serial/protocol/printer_report.hpp):
// M114 answers of Marlin, Prusa, Klipper and RepRapFirmware, and the last
// line a line error names.
#include <catch2/catch.hpp>

#include "gcode/serial/protocol/printer_report.hpp"

using namespace gcode::serial;

TEST_CASE("printer report: M114 of every firmware, step counts ignored", "[serial][journal]") {
  auto marlin = parse_position_report("X:10.00 Y:20.50 Z:0.30 E:12.00 Count X:800 Y:1640 Z:120");
  REQUIRE(marlin);
  CHECK(marlin->axis[0] == 10.0);
  CHECK(marlin->axis[1] == 20.5);
  CHECK(marlin->axis[2] == 0.3);
  CHECK(marlin->axis[3] == 12.0);
  CHECK(marlin->present[3]);
  auto klipper = parse_position_report("ok X:10.000 Y:-2.000 Z:5.000 E:0.000");
  REQUIRE(klipper);
  CHECK(klipper->axis[1] == -2.0);
  auto rrf = parse_position_report("X:1.000 Y:2.000 Z:3.000 E:0.0 Count 80 160 1200 Machine 1.000 2.000 3.000");
  REQUIRE(rrf);
  CHECK(rrf->axis[2] == 3.0);
  auto no_e = parse_position_report("X:1 Y:2 Z:3");
  REQUIRE(no_e);
  CHECK_FALSE(no_e->present[3]);
  // Not position reports.
  CHECK_FALSE(parse_position_report("ok"));
  CHECK_FALSE(parse_position_report("T:210.0 /210.0 B:60.0 /60.0"));
  CHECK_FALSE(parse_position_report("Count X:800 Y:1640 Z:120"));
  CHECK_FALSE(parse_position_report("X:ab Y:2 Z:3"));
  CHECK_FALSE(parse_position_report("echo:busy: processing"));
}

TEST_CASE("printer report: the last line a line error names", "[serial][journal]") {
  CHECK(last_line_of("Line Number is not Last Line Number+1, Last Line: 1234") == 1234);
  CHECK(last_line_of("checksum mismatch, Last Line: 0") == 0);
  CHECK(last_line_of("No Checksum with line number, Last Line:7") == 7);
  CHECK_FALSE(last_line_of("Unknown command: \"G999\""));
  CHECK_FALSE(last_line_of("Last Line: none"));
}

TEST_CASE("printer report: where the printer stands against where it should, axis by axis",
          "[serial][printer_report]") {
  using gcode::serial::axis_off;
  const auto report = gcode::serial::parse_position_report("X:10.00 Y:20.00 Z:0.30 E:12.00 Count X:800 Y:1600 Z:120");
  REQUIRE(report);
  CHECK(axis_off(*report, {10, 20, 0.3}, 0.01) == -1);
  CHECK(axis_off(*report, {10.005, 19.995, 0.3}, 0.01) == -1);  // within the tolerance
  CHECK(axis_off(*report, {10, 20.5, 0.3}, 0.01) == 1);
  CHECK(axis_off(*report, {9, 20, 0.5}, 0.01) == 0);  // the first axis off
  CHECK(axis_off(*report, {10, 20, 0.5}, 0.01) == 2);
  CHECK(axis_off(*report, {10, 20, 0.5}, 0.5) == -1);
  // An axis the report does not name is not held against it.
  gcode::serial::PositionReport partial = *report;
  partial.present[2] = false;
  CHECK(axis_off(partial, {10, 20, 5}, 0.01) == -1);
}
