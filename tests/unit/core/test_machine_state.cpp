#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <catch2/catch.hpp>

#include "gcode/core/machine_state.hpp"
#include "test_support.hpp"

using gcode::kE;
using gcode::kX;
using gcode::kY;
using gcode::kZ;

namespace {
gcode::Move apply(gcode::MachineState& s, const char* text) { return s.apply(gcode::Line::parse(text)); }
}  // namespace

TEST_CASE("absolute and relative extrusion count the same filament", "[machine_state]") {
  gcode::MachineState a;
  apply(a, "M82");
  apply(a, "G1 X10 E1");
  auto m = apply(a, "G1 X20 E1.5");
  CHECK(m.filament == Approx(0.5));
  CHECK(m.extruding);
  gcode::MachineState r;
  apply(r, "M83");
  apply(r, "G1 X10 E1");
  m = apply(r, "G1 X20 E0.5");
  CHECK(m.filament == Approx(0.5));
  CHECK(r.filament_total == Approx(1.5));
}

TEST_CASE("Marlin couples E to G90/G91", "[machine_state]") {
  gcode::MachineState s;
  apply(s, "M83");
  CHECK(s.relative_e);
  apply(s, "G91");
  CHECK(s.relative_xyz);
  CHECK(s.relative_e);
  apply(s, "G90");
  CHECK_FALSE(s.relative_e);  // G90 makes E absolute again even after M83
  apply(s, "G91");
  apply(s, "M82");
  CHECK(s.relative_xyz);
  CHECK_FALSE(s.relative_e);
}

TEST_CASE("G92 shifts coordinates without moving, filament is unaffected", "[machine_state]") {
  gcode::MachineState s;
  apply(s, "G1 X10 Y10 E5");
  apply(s, "G92 E0");
  CHECK(s.position[kE] == 0);
  CHECK(s.machine(kE) == Approx(5));
  auto m = apply(s, "G1 X20 E1");
  CHECK(m.filament == Approx(1));
  CHECK(s.filament_total == Approx(6));
  apply(s, "G92 X0");
  CHECK(s.position[kX] == 0);
  CHECK(s.machine(kX) == Approx(20));
}

TEST_CASE("inches are converted to mm, F too", "[machine_state]") {
  gcode::MachineState s;
  apply(s, "G20");
  auto m = apply(s, "G1 X1 F60");
  CHECK(s.position[kX] == Approx(25.4));
  CHECK(m.feedrate == Approx(60 * 25.4));
  apply(s, "G21");
  apply(s, "G1 X1");
  CHECK(s.position[kX] == Approx(1));
}

TEST_CASE("inches too many to be millimetres saturate at the exact range, as mm values do", "[machine_state]") {
  // (fuzz_pipeline under UBSan: 1e8 in was multiplied by 254 past int64.)
  gcode::MachineState s;
  apply(s, "G20");
  apply(s, "G1 X100000000 Y-100000000");
  CHECK(s.exact[kX] == gcode::Fixed::from_units(gcode::Fixed::kMax));
  CHECK(s.exact[kY] == gcode::Fixed::from_units(-gcode::Fixed::kMax));
  apply(s, "G1 X1000");  // within range: exact
  CHECK(s.position[kX] == Approx(25400));
}

TEST_CASE("G91 relative moves and travel vs extrusion", "[machine_state]") {
  gcode::MachineState s;
  apply(s, "G1 X5 Y5 Z1");
  apply(s, "G91");
  auto m = apply(s, "G1 X3 Y4");
  CHECK(m.length == Approx(5));
  CHECK(m.travel);
  CHECK(s.position[kX] == Approx(8));
  m = apply(s, "G1 E-2");
  CHECK(m.retraction());
  CHECK_FALSE(m.travel);
}

TEST_CASE("firmware retraction: bare G10/G11 only", "[machine_state]") {
  gcode::MachineState s;
  auto m = apply(s, "G10");
  CHECK(m.kind == gcode::MoveKind::FirmwareRetract);
  CHECK(s.firmware_retracted);
  apply(s, "G11");
  CHECK_FALSE(s.firmware_retracted);
  m = apply(s, "G10 P0 S210");  // RepRapFirmware tool temperature
  CHECK(m.kind == gcode::MoveKind::None);
  CHECK_FALSE(s.firmware_retracted);
}

TEST_CASE("arcs: length of I/J and R forms, full circle", "[machine_state][arc]") {
  gcode::MachineState s;
  apply(s, "G1 X0 Y0");
  auto m = apply(s, "G3 X10 Y0 I5 J0 E1");
  CHECK(m.xy_length == Approx(3.14159265 * 5));
  m = apply(s, "G2 X10 Y0 I-5 J0");  // start == end: full circle
  CHECK(m.xy_length == Approx(2 * 3.14159265 * 5));
  apply(s, "G1 X0 Y0");
  m = apply(s, "G2 X10 Y10 R10");
  CHECK(m.xy_length == Approx(3.14159265 * 10 / 2));
  m = apply(s, "G2 X0 Y0 R-10");  // negative R: the long way
  CHECK(m.xy_length == Approx(3 * 3.14159265 * 10 / 2));
}

TEST_CASE("arcs: Marlin's P word adds full turns, a bad P is no arc", "[machine_state][arc]") {
  gcode::MachineState s;
  apply(s, "G1 X0 Y0");
  auto m = apply(s, "G3 X10 Y0 I5 J0 P2 Z1");  // two turns, then the half circle, rising 1 mm
  CHECK(m.xy_length == Approx(5 * 3.14159265 * 5));
  CHECK(m.length == Approx(std::hypot(5 * 3.14159265 * 5, 1.0)));
  m = apply(s, "G2 I-5 J0 P1");  // back to its start: a full circle after one extra turn
  CHECK(m.xy_length == Approx(2 * 2 * 3.14159265 * 5));
  m = apply(s, "G2 I-5 J0 P1.5");  // not a whole number: read as the straight move it names
  CHECK(m.xy_length == 0);
}

TEST_CASE("malformed moves are ignored, unknown commands are harmless", "[machine_state]") {
  gcode::MachineState s;
  apply(s, "G1 X5");
  auto m = apply(s, "G1 X1e309 E5");
  CHECK(m.ignored);
  CHECK(s.position[kX] == 5);
  apply(s, "M999 X1");
  apply(s, "G29.1 X9");
  apply(s, "FOO_BAR X=1");
  CHECK(s.position[kX] == 5);
}

TEST_CASE("temperatures, fan, tools, homing", "[machine_state]") {
  gcode::MachineState s;
  apply(s, "M104 S210");
  apply(s, "M109 R200 T1");
  apply(s, "M190 S60");
  apply(s, "M106 S128");
  apply(s, "T1");
  CHECK(s.hotend_target[0] == 210);
  CHECK(s.hotend_target[1] == 200);
  CHECK(s.bed_target == 60);
  CHECK(s.fan == 128);
  CHECK(s.tool == 1);
  apply(s, "G1 X5 Y5 Z5");
  apply(s, "G28 Z");
  CHECK(s.position[kZ] == 0);
  CHECK(s.position[kX] == 5);
}

TEST_CASE("Z-hop: a lift that comes back down before extruding", "[machine_state]") {
  gcode::MachineState s;
  apply(s, "G1 Z0.2");
  apply(s, "G1 X10 E1");
  auto lift = apply(s, "G1 Z0.6");
  CHECK(lift.z_lift);
  CHECK(s.lifted);
  CHECK_FALSE(apply(s, "G1 X20 Y5").z_hop_return);
  auto back = apply(s, "G1 Z0.2");
  CHECK(back.z_hop_return);
  CHECK_FALSE(s.lifted);
  // A lift followed by extrusion up there was a layer change, not a hop.
  apply(s, "G1 Z0.4");
  apply(s, "G1 X0 E2");
  CHECK_FALSE(s.lifted);
  CHECK_FALSE(apply(s, "G1 Z0.2").z_hop_return);
}

TEST_CASE("a relative E move's filament is the exact difference's double, bit for bit, on every fixture",
          "[machine_state]") {
  // The filament of a plain relative E word is taken from the word's own
  // value instead of dividing the exact difference: the same double.
  std::size_t relative = 0;
  for (const std::string& name : gctest::fixture_names()) {
    std::string text = gctest::read_file(gctest::fixture_path(name));
    gcode::MachineState s = gctest::initial_state(text);
    for (const std::string& raw : gctest::split_lines(text)) {
      gcode::Line line = gcode::Line::parse(raw);
      const gcode::Fixed before = s.exact[kE];
      const bool was_relative = s.relative_e;
      gcode::Move m = s.apply(line);
      if (line.find('E') == nullptr || !(line.is_g(0) || line.is_g(1) || line.is_g(2) || line.is_g(3))) continue;
      const double exact = (s.exact[kE] - before).to_double();
      if (std::memcmp(&m.filament, &exact, sizeof exact) != 0) {
        FAIL_CHECK(name << ": " << raw << ": " << m.filament << " against " << exact);
        break;
      }
      relative += was_relative ? 1 : 0;
    }
  }
  CHECK(relative > 10000);
  // Junk at the edges: saturation, a signed zero, nine decimals, huge values.
  gcode::MachineState r;
  apply(r, "M83");
  for (const char* t : {"G1 E-0", "G1 E0.000000001", "G1 E-0.000000001", "G1 E9000000000", "G1 E9000000000",
                        "G1 E-9000000000", "G1 E123456.123456789", "G1 E9007199.254740993"}) {
    const gcode::Fixed before = r.exact[kE];
    gcode::Move m = apply(r, t);
    const double exact = (r.exact[kE] - before).to_double();
    INFO(t);
    CHECK(std::memcmp(&m.filament, &exact, sizeof exact) == 0);
  }
}

TEST_CASE("read_heater_fan: a heater or fan index past int's range is clamped, not converted out of range",
          "[machine_state]") {
  // (fuzz_pipeline: "T6.7e64" was converted to int, undefined behaviour.)
  gcode::HeaterFanLine out;
  REQUIRE(gcode::read_heater_fan(gcode::Line::parse("M104 T66666666666666666666666666666666666666666666666666666666666666666 S200"), 0, out));
  CHECK(out.index == std::numeric_limits<int>::max());
  REQUIRE(gcode::read_heater_fan(gcode::Line::parse("M106 P-9999999999999999999999 S255"), 0, out));
  CHECK(out.index == std::numeric_limits<int>::min());
  REQUIRE(gcode::read_heater_fan(gcode::Line::parse("M104 T1 S200"), 0, out));
  CHECK(out.index == 1);
}
