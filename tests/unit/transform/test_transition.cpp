// Transition (transform/transition.hpp): the one way from one machine state
// to another. Each step writes a line only where the printer differs, the
// builder knows the printer as its lines leave it, and the whole way
// (between) brings a printer to the target state exactly, a reset printer
// included: replayed through MachineState, the state after the lines is the
// target's.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/transform/transition.hpp"
#include "test_support.hpp"

using gcode::Fixed;
using gcode::kE;
using gcode::kX;
using gcode::kY;
using gcode::kZ;
using gcode::MachineState;
using gcode::Transition;
using Lines = std::vector<std::string>;

namespace {


struct TransitionReplay {
  MachineState after;
  double net = 0;        // filament the lines pushed
  double lowest_xy_z = 1e300;  // the lowest Z of any XY travel
};

TransitionReplay replay(const MachineState& from, const Lines& lines) {
  TransitionReplay r;
  r.after = from;
  for (const std::string& text : lines) {
    gcode::Move m = r.after.apply(gcode::Line::parse(text));
    r.net += m.filament;
    if (m.xy_length > 0) r.lowest_xy_z = std::min(r.lowest_xy_z, m.end[kZ]);
  }
  return r;
}

// What a resume must bring back: everything the next line of the file relies on.
void require_at(const MachineState& a, const MachineState& b) {
  for (int axis : {kX, kY, kZ, kE}) {
    INFO("axis " << axis);
    CHECK(a.at(axis) == b.at(axis));
  }
  CHECK(a.relative_xyz == b.relative_xyz);
  CHECK(a.relative_e == b.relative_e);
  CHECK(a.feedrate == b.feedrate);
  CHECK(a.firmware_retracted == b.firmware_retracted);
  CHECK(a.tool == b.tool);
  CHECK(a.hotend_target == b.hotend_target);
  CHECK(a.bed_target == b.bed_target);
  CHECK(a.fan == b.fan);
  CHECK(a.speed_factor == b.speed_factor);
  CHECK(a.flow_factor == b.flow_factor);
}

}  // namespace

TEST_CASE("transition: mode steps write only what differs", "[transition]") {
  MachineState s = gctest::replay_state("G28\nM83\nG1 X10 Y10 Z1 F1200\n");
  Lines out;
  Transition t(s, gctest::kPrecision, out);
  t.positioning(false);
  t.e_mode(true);
  t.e_coordinate(s.at(kE));
  t.feed_rate(1200);
  t.firmware_retraction(false);
  t.tool(0);
  CHECK(out.empty());
  t.positioning(true);
  t.e_mode(false);
  t.e_coordinate(Fixed::from_double(3.5));
  t.feed_rate(3000);
  t.firmware_retraction(true);
  t.tool(1);
  CHECK(out == Lines{"G91", "M82", "G92 E3.5", "G1 F3000", "G10", "T1"});
  // The builder follows its lines: the printer is as they leave it.
  CHECK(t.printer().relative_xyz);
  CHECK_FALSE(t.printer().relative_e);
  CHECK(t.printer().at(kE) == Fixed::from_double(3.5));
  CHECK(t.printer().tool == 1);
  // Forced, a line is written even where the printer agrees.
  t.e_mode(false, true);
  t.e_coordinate(Fixed::from_double(3.5), true);
  CHECK(out.back() == "G92 E3.5");
  CHECK(out.at(out.size() - 2) == "M82");
}

TEST_CASE("transition: E moves in the printer's mode, coordinate and pieces", "[transition]") {
  MachineState s = gctest::replay_state("G28\nM82\nG1 X10 Y10 Z1 F1200\nG1 X20 E5.0348\n");
  Lines out;
  Transition t(s, gctest::kPrecision, out);
  t.extrude(-Fixed::from_double(0.8), 2100);
  t.extrude(Fixed(), 2100);  // nothing to push: no line
  t.extrude_mm(0.8, 35);
  CHECK(out == Lines{"G1 E4.2348 F2100", "G1 E5.0348 F2100"});
  CHECK(t.net_filament().is_zero());
  // Relative E writes amounts; long pushes go in pieces the firmware takes.
  MachineState r = gctest::replay_state("G28\nM83\nG1 X10 Y10 Z1\n");
  Lines long_out;
  Transition u(r, gctest::kPrecision, long_out);
  u.extrude_mm(320, 50);
  CHECK(long_out == Lines{"G1 E150 F3000", "G1 E150 F3000", "G1 E20 F3000"});
  CHECK(u.net_filament() == Fixed::from_int(320));
}

TEST_CASE("transition: moves, safe height and heaters", "[transition]") {
  MachineState s = gctest::replay_state("G28\nM104 S200\nM140 S60\nG1 X10 Y10 Z1\n");
  Lines out;
  Transition t(s, gctest::kPrecision, out, {.lift = 2, .max_z = 0, .z_feed = 600, .xy_feed = 3000, .g0 = false});
  CHECK(t.safe_z(Fixed::from_double(1.23456)) == Fixed::from_double(3.235));
  t.move_z(Fixed::from_double(3));
  t.move_xy(Fixed::from_double(20.5), Fixed::from_int(30));
  CHECK(out == Lines{"G1 Z3 F600", "G1 X20.5 Y30 F3000"});
  out.clear();
  // Waiting for a heater that cools needs R (Marlin's S waits only while heating).
  t.hotend(0, 180, true, false);
  t.hotend(1, 210, false, true);
  t.bed(70, true);
  t.fan(128);
  t.fan(0);
  CHECK(out == Lines{"M109 R180", "M104 T1 S210", "M190 S70", "M106 S128", "M107"});
  // A printer's height limit caps the lift.
  Lines capped;
  Transition c(s, gctest::kPrecision, capped, {.lift = 5, .max_z = 4});
  CHECK(c.safe_z(Fixed::from_int(1)) == Fixed::from_int(4));
}

TEST_CASE("transition: between two running states returns the printer exactly", "[transition]") {
  MachineState from =
      gctest::replay_state("G28\nM82\nM104 S215\nM140 S60\nG1 X100 Y100 Z5 F1200\nG1 X110 E42.5\nG91\n");
  MachineState to = gctest::replay_state(
      "G28\nM83\nM104 S205\nM140 S60\nM106 S255\nM220 S90\nM221 S95\nG1 X20 Y30 Z2.4 F2400\nG1 E-0.8\n");
  Lines out;
  Transition t(from, gctest::kPrecision, out);
  Transition::Between how;
  how.top_z = 5;
  how.retracted_to = 0.8;
  t.between(to, how);
  TransitionReplay r = replay(from, out);
  require_at(r.after, to);
  // The travel is above everything printed; the E moves end as retracted as the target.
  CHECK(r.lowest_xy_z > 5);
  CHECK(r.net == Approx(-0.8));
  CHECK(out.front() == "M104 S205");  // falls: set, not waited for
}

TEST_CASE("transition: between from a reset printer heats, homes X Y, declares Z and restores", "[transition]") {
  // After a reset: nothing known, heaters off, modes default.
  const MachineState reset;
  MachineState to = gctest::replay_state(
      "G28\nM83\nM140 S60\nM104 S215\nM106 S200\nG1 X50 Y60 Z12.2 F1800\nG92 E0\nG1 X55 E1.5\n");
  Lines out;
  Transition t(reset, gctest::kPrecision, out, {.lift = 1, .e_feed = 1800});
  Transition::Between how;
  how.top_z = 12.2;
  how.nozzle_z = 12.4;  // where the user says the nozzle stands
  how.prime = 3;
  t.between(to, how);
  // Bed first, then the nozzle, both waited for; X and Y homed, Z declared,
  // never homed; the lift clears the part; the prime at the target.
  REQUIRE(out.size() >= 6);
  CHECK(out[0] == "M190 S60");
  CHECK(out[1] == "M109 S215");
  CHECK(out[2] == "G28 X Y");
  CHECK(out[3] == "G92 Z12.4");
  for (const std::string& l : out) CHECK(l.rfind("G28 Z", 0) == std::string::npos);
  CHECK(std::find(out.begin(), out.end(), "G0 Z13.4 F600") != out.end());
  CHECK(std::find(out.begin(), out.end(), "G1 E3 F1800") != out.end());
  TransitionReplay r = replay(reset, out);
  require_at(r.after, to);
  CHECK(r.lowest_xy_z > 12.2);
  CHECK(r.net == Approx(3));
}

TEST_CASE("transition: between says what it cannot know", "[transition]") {
  const MachineState reset;
  MachineState to = gctest::replay_state("G28\nG1 X50 Y60 Z2\n");
  Lines out;
  Transition t(reset, gctest::kPrecision, out);
  // Z unknown and no height given: the part is under the nozzle, no homing.
  CHECK_THROWS_AS(t.between(to, {}), std::invalid_argument);
  Transition u(to, gctest::kPrecision, out);
  CHECK_THROWS_AS(u.between(reset, {}), std::invalid_argument);  // nowhere known to go
  MachineState inches = gctest::replay_state("G28\nG20\nG1 X1 Y1 Z1\n");
  Transition v(inches, gctest::kPrecision, out);
  CHECK_THROWS_AS(v.between(to, {}), std::invalid_argument);
}
