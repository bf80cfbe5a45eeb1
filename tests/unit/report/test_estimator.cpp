#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "gcode/report/estimator.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/report/planner_limits.hpp"
#include "slicer_time.hpp"
#include "test_support.hpp"

namespace {

// Runs G-code lines through MachineState and an Estimator; returns the total.
double run(const std::vector<std::string>& lines, gcode::EstimatorOptions o = {}) {
  gcode::MachineState state;
  gcode::Estimator e(o);
  for (const std::string& l : lines) {
    gcode::Line line = gcode::Line::parse(l);
    e.add(line, state.apply(line));
  }
  e.finish();
  CHECK(e.queued() == 0);
  return e.elapsed();
}

// Junction deviation starts and ends every stop at 0 mm/s: exact textbook trapezoids.
const std::vector<std::string> kSetup = {"M204 P1000 T1000 R1000", "M205 J0.02", "G1 F6000"};

std::vector<std::string> with_setup(std::vector<std::string> moves) {
  std::vector<std::string> all = kSetup;
  all.insert(all.end(), moves.begin(), moves.end());
  return all;
}

// Accelerate from v0 and decelerate to v1 around a cruise at vn (a = 1000).
double trapezoid(double length, double v0, double vn, double v1, double a = 1000) {
  double da = (vn * vn - v0 * v0) / (2 * a), dd = (vn * vn - v1 * v1) / (2 * a);
  return (vn - v0) / a + (vn - v1) / a + (length - da - dd) / vn;
}

}  // namespace

TEST_CASE("a single long move is an exact trapezoid", "[estimator]") {
  // 100 mm at 100 mm/s, 1000 mm/s^2: 0.1 s up over 5 mm, 90 mm cruising, 0.1 s down.
  CHECK(run(with_setup({"G1 X100"})) == Approx(1.1).epsilon(1e-9));
}

TEST_CASE("two collinear moves do not slow down at the junction", "[estimator]") {
  CHECK(run(with_setup({"G1 X50", "G1 X100"})) == Approx(1.1).epsilon(1e-9));
  // Many short collinear pieces: still one trapezoid.
  std::vector<std::string> pieces;
  for (int i = 1; i <= 100; ++i) pieces.push_back("G1 X" + std::to_string(i));
  CHECK(run(with_setup(pieces)) == Approx(1.1).epsilon(1e-9));
}

TEST_CASE("a 90 degree corner slows to the junction deviation speed", "[estimator]") {
  // Marlin: v^2 = a * J * sin(theta/2) / (1 - sin(theta/2)), theta = 90 degrees.
  double s = std::sqrt(0.5);
  double vj = std::sqrt(1000 * 0.02 * s / (1 - s));
  double expected = 2 * trapezoid(50, 0, 100, vj);
  CHECK(run(with_setup({"G1 X50", "G1 Y50"})) == Approx(expected).epsilon(1e-9));
  CHECK(vj == Approx(6.949).epsilon(1e-3));
  // A full reversal stops.
  CHECK(run(with_setup({"G1 X50", "G1 X0"})) == Approx(2 * trapezoid(50, 0, 100, 0)).epsilon(1e-9));
}

TEST_CASE("a move too short to reach cruise speed is a triangle", "[estimator]") {
  // 4 mm would need 10 mm to reach 100 mm/s: the peak is sqrt(a * L).
  double peak = std::sqrt(1000.0 * 4);
  CHECK(run(with_setup({"G1 X4"})) == Approx(2 * peak / 1000).epsilon(1e-9));
}

TEST_CASE("classic jerk starts and ends at the safe speed", "[estimator]") {
  // M205 X10: the move may start and stop at 10 mm/s instantly.
  double expected = trapezoid(100, 10, 100, 10);
  CHECK(run({"M204 P1000 T1000", "M205 X10 Y10 Z0.3 E5", "G1 F6000", "G1 X100"}) == Approx(expected).epsilon(1e-9));
  // A 90 degree corner at 100 mm/s: each axis changes by the whole speed,
  // more than 10, so the junction is scaled to 10 mm/s.
  double corner = 2 * trapezoid(50, 10, 100, 10);
  CHECK(run({"M204 P1000 T1000", "M205 X10 Y10 Z0.3 E5", "G1 F6000", "G1 X50", "G1 Y50"}) ==
        Approx(corner).epsilon(1e-9));
}

TEST_CASE("per-axis limits cap speed and acceleration", "[estimator]") {
  // M203 X50: F6000 on X is cut to 50 mm/s; M201 X500 caps the acceleration.
  double expected = trapezoid(100, 0, 50, 0, 500);
  CHECK(run(with_setup({"M203 X50", "M201 X500", "G1 X100"})) == Approx(expected).epsilon(1e-9));
  // M220 S50 halves the feed rate.
  CHECK(run(with_setup({"M220 S50", "G1 X100"})) == Approx(trapezoid(100, 0, 50, 0)).epsilon(1e-9));
}

TEST_CASE("M220 B backs up the feed rate percentage and M220 R restores it", "[estimator]") {
  // Marlin 2 and Prusa firmware: B before S in one line saves the old value.
  double half = trapezoid(100, 0, 50, 0), full = trapezoid(100, 0, 100, 0);
  CHECK(run(with_setup({"M220 B S50", "G1 X100", "M400", "M220 R", "G1 X0"})) == Approx(half + full).epsilon(1e-9));
  CHECK(run(with_setup({"M220 S50", "M220 B", "M220 S100", "M220 R", "G1 X100"})) == Approx(half).epsilon(1e-9));
}

TEST_CASE("E-only moves use the retract acceleration and the E feed limit", "[estimator]") {
  // 5 mm at F2700 = 45 mm/s, capped by Marlin's default E max of 25 mm/s; R2000.
  double expected = trapezoid(5, 0, 25, 0, 2000);
  CHECK(run({"M204 P1000 T1000 R2000", "M205 J0.02", "M83", "G1 E-5 F2700"}) == Approx(expected).epsilon(1e-9));
}

TEST_CASE("firmware retraction is an E move at the firmware's retract and recover speeds", "[estimator]") {
  // RepRapFirmware (the M566, E jerk 1 mm/s): no retract acceleration, so the
  // print one; its defaults are 2 mm at 1000 mm/min both ways. The dwell
  // stops the machine between the two: each starts and ends at the jerk speed.
  std::vector<std::string> rrf = {"M566 E60", "M201 E10000", "M203 E3600", "M204 P1000 T1000", "G10", "G4 S0", "G11"};
  double v = 1000.0 / 60;
  CHECK(run(rrf) == Approx(2 * trapezoid(2, 1, v, 1)).epsilon(1e-9));
  // RepRapFirmware's M207: S length, R extra on recover, F retract and T recover speed (mm/min).
  rrf.insert(rrf.begin(), "M207 S0.8 R0.2 F1200 T900");
  CHECK(run(rrf) == Approx(trapezoid(0.8, 1, 20, 1) + trapezoid(1.0, 1, 15, 1)).epsilon(1e-9));
}

TEST_CASE("RepRapFirmware takes its own firmware retraction defaults unless the file or profile set them", "[estimator][planner_limits]") {
  gcode::PlannerLimits marlin;
  CHECK(marlin.fw_retract_length == 3);  // Marlin's FWRETRACT defaults
  CHECK(marlin.fw_retract_speed == 45);
  CHECK(marlin.fw_unretract_speed == 8);
  gcode::PlannerLimits by_m566;
  by_m566.apply(gcode::Line::parse("M566 X480 Y480 Z24 E270"));
  CHECK(by_m566.fw_retract_length == 2);
  CHECK(by_m566.fw_retract_speed == Approx(1000.0 / 60));
  CHECK(by_m566.fw_unretract_speed == Approx(1000.0 / 60));
  CHECK(by_m566.fw_unretract_extra == 0);
  gcode::PlannerLimits by_flavor;
  by_flavor.load_profile_text("; gcode_flavor = reprapfirmware\n");
  CHECK(by_flavor.firmware == gcode::Firmware::RepRapFirmware);
  CHECK(by_flavor.fw_retract_length == 2);
  // What the printer was told wins, whichever comes first.
  gcode::PlannerLimits told;
  told.apply(gcode::Line::parse("M207 S0.8 F2100"));
  told.apply(gcode::Line::parse("M566 X480"));
  CHECK(told.fw_retract_length == Approx(0.8));
  CHECK(told.fw_retract_speed == Approx(35));
  gcode::PlannerLimits profiled;
  profiled.load_profile_text("fw_unretract_speed = 30\ngcode_flavor = reprapfirmware\n");
  CHECK(profiled.fw_unretract_speed == 30);
  CHECK(profiled.fw_retract_length == 3);
}

TEST_CASE("an arc is timed along its length and a helix back to its start is no Z move", "[estimator]") {
  // Half circle r 5 at 100 mm/s: 5 pi mm, an exact trapezoid (junction deviation stops at 0).
  double half = 5 * 3.141592653589793;
  CHECK(run(with_setup({"G1 X0 Y0 F6000", "G4 S0", "G3 X10 Y0 I5 J0"})) == Approx(trapezoid(half, 0, 100, 0)).epsilon(1e-9));
  // A full circle r 5 rising 1 mm: 31.4 mm of XY and 1 mm of Z. Its Z share
  // (1/31.4 of 100 mm/s) is within Marlin's default Z limits (5 mm/s, 100 mm/s^2 / 0.032).
  double circle = 10 * 3.141592653589793, helix = std::hypot(circle, 1.0);
  CHECK(run(with_setup({"G1 X0 Y0 F6000", "G4 S0", "G2 Z1 I5 J0"})) == Approx(trapezoid(helix, 0, 100, 0)).epsilon(1e-9));
  // P1 (Marlin's ARC_P_CIRCLES): one more turn before it, the same 1 mm of Z.
  double two_turns = std::hypot(2 * circle, 1.0);
  CHECK(run(with_setup({"G1 X0 Y0 F6000", "G4 S0", "G2 Z1 I5 J0 P1"})) ==
        Approx(trapezoid(two_turns, 0, 100, 0)).epsilon(1e-9));
}

TEST_CASE("dwells, heating and homing add their time", "[estimator]") {
  gcode::EstimatorOptions o;
  o.home_time = 7;
  o.hotend_heat_rate = 2;
  o.bed_heat_rate = 0.5;
  o.ambient = 25;
  CHECK(run({"G4 P1500"}, o) == Approx(1.5));
  CHECK(run({"G4 S2"}, o) == Approx(2));
  CHECK(run({"G28"}, o) == Approx(7));
  CHECK(run({"M109 S215"}, o) == Approx(95));   // 190 degrees at 2 per second
  CHECK(run({"M190 S60"}, o) == Approx(70));    // 35 degrees at 0.5 per second
  // Heating while the machine does something else shortens the wait.
  CHECK(run({"M104 S215", "G4 S45", "M109 S215"}, o) == Approx(95));
  o.heat_time = false;
  CHECK(run({"M109 S215", "M190 S60"}, o) == 0);
}

TEST_CASE("a short look-ahead is slower only where it must be", "[estimator]") {
  std::vector<std::string> pieces = with_setup({});
  for (int i = 1; i <= 1000; ++i) pieces.push_back("G1 X" + std::to_string(i * 0.1));
  gcode::EstimatorOptions wide;
  gcode::EstimatorOptions narrow;
  narrow.lookahead = 4;
  double t_wide = run(pieces, wide), t_narrow = run(pieces, narrow);
  CHECK(t_wide == Approx(1.1).epsilon(1e-6));
  // Four 0.1 mm blocks are not enough to stop from 100 mm/s: the planner
  // must keep the speed low enough to stop within its window.
  CHECK(t_narrow > t_wide * 2);
}

TEST_CASE("time so far and time queued add up to the final total", "[estimator]") {
  std::string text = gctest::read_file(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode"));
  gcode::MemoryLineSplitter lines(text);
  gcode::RawLine raw;
  gcode::MachineState state;
  gcode::Estimator e;
  double last = 0;
  bool monotonic = true;
  std::size_t n = 0;
  while (lines.next(raw)) {
    gcode::Line line = gcode::Line::parse(raw.text);
    e.add(line, state.apply(line));
    if (++n % 997 == 0) {
      if (e.elapsed() < last) monotonic = false;
      CHECK(e.total() >= e.elapsed());
      last = e.elapsed();
    }
  }
  double before_finish = e.total();
  e.finish();
  CHECK(monotonic);
  CHECK(e.elapsed() == Approx(before_finish).epsilon(1e-9));
  CHECK(e.breakdown().total() == Approx(e.elapsed()).epsilon(1e-9));
}

TEST_CASE("machine limits from M201/M203/M204/M205, M566 and profiles", "[estimator][planner_limits]") {
  gcode::PlannerLimits l;
  CHECK(l.apply(gcode::Line::parse("M201 X1000 Y900 Z200 E5000")));
  CHECK(l.apply(gcode::Line::parse("M203 X200 Y200 Z12 E120")));
  CHECK(l.apply(gcode::Line::parse("M204 P1250 R1250 T1500")));
  CHECK(l.apply(gcode::Line::parse("M205 X8 Y8 Z0.4 E4.5")));
  CHECK(!l.apply(gcode::Line::parse("G1 X5")));
  CHECK(l.max_acceleration[1] == 900);
  CHECK(l.max_feedrate[3] == 120);
  CHECK(l.travel_acceleration == 1500);
  CHECK(l.jerk[3] == 4.5);
  CHECK(l.junction_deviation == 0);
  l.apply(gcode::Line::parse("M204 S3000"));
  CHECK(l.print_acceleration == 3000);
  CHECK(l.travel_acceleration == 3000);
  l.apply(gcode::Line::parse("M205 J0.013"));
  CHECK(l.junction_deviation == Approx(0.013));

  // RepRapFirmware: M203 in mm/min, recognised by the M566 that follows.
  gcode::PlannerLimits r;
  r.apply(gcode::Line::parse("M203 X12000 Y12000 Z720 E3600"));
  r.apply(gcode::Line::parse("M566 X480 Y480 Z24 E300"));
  CHECK(r.firmware == gcode::Firmware::RepRapFirmware);
  CHECK(r.max_feedrate[0] == Approx(200));
  CHECK(r.jerk[0] == Approx(8));

  // PrusaSlicer config keys (first value = normal mode) cap M204.
  gcode::PlannerLimits p;
  CHECK(p.load_profile_text("; machine_max_acceleration_extruding = 1500,1250\n"
                            "; machine_max_feedrate_x = 500,200\n; unrelated = 3\n# comment\n") == 2);
  CHECK(p.max_feedrate[0] == 500);
  p.apply(gcode::Line::parse("M204 S3000"));
  CHECK(p.print_acceleration == 1500);
  CHECK_THROWS_AS(p.load_profile_text("max_feedrate_x = fast\n"), std::invalid_argument);
  CHECK(!gcode::PlannerLimits::preset("cura").empty());
  gcode::PlannerLimits c;
  CHECK(c.load_profile("cura") > 10);
  CHECK(c.print_acceleration == 4000);
  CHECK_THROWS(c.load_profile("/nonexistent/profile.ini"));
}

TEST_CASE("format_duration writes h:mm:ss", "[estimator]") {
  CHECK(gcode::format_duration(0) == "0:00:00");
  CHECK(gcode::format_duration(59.6) == "0:01:00");
  CHECK(gcode::format_duration(4454) == "1:14:14");
  CHECK(gcode::format_duration(100000) == "27:46:40");
}

// The slicers' own estimates, against ours with the limits the slicer used:
// PrusaSlicer's come with the file (M201... lines, or its config block),
// Cura's are the "cura" profile (CuraEngine's machine defaults). Heating is
// left out, as both slicers leave it out.
TEST_CASE("fixture estimates are within 5 % of PrusaSlicer's and 10 % of Cura's", "[estimator][fixtures]") {
  int compared = 0;
  for (const std::string& name : gctest::fixture_names()) {
    std::string path = gctest::fixture_path(name);
    std::string text = gctest::read_file(path);
    gctest::SlicerTime slicer = gctest::slicer_time(text);
    if (!slicer.found) continue;
    gcode::EstimatorOptions o;
    o.heat_time = false;
    if (slicer.cura) {
      o.limits.load_profile("cura");
    } else {
      // The config block at the end, as gc-layers reads it from a file.
      std::size_t at = text.find("; prusaslicer_config = begin");
      REQUIRE(at != std::string::npos);
      o.limits.load_profile_text(std::string_view(text).substr(at));
      // PrusaSlicer gives G10/G11 no time at all; the printer does retract (see
      // the test below): compare the rest of the model.
      if (text.find("; use_firmware_retraction = 1") != std::string::npos)
        o.limits.load_profile_text("fw_retract_length = 0\nfw_unretract_extra = 0\n");
    }
    gcode::MemoryLineSplitter lines(text);
    gcode::RawLine raw;
    gcode::MachineState state;
    gcode::Estimator e(o);
    while (lines.next(raw)) {
      gcode::Line line = gcode::Line::parse(raw.text);
      e.add(line, state.apply(line));
    }
    e.finish();
    double error = (e.elapsed() - slicer.seconds) / slicer.seconds;
    INFO(name << ": slicer " << slicer.seconds << " s, ours " << e.elapsed() << " s, error " << error * 100 << " %");
    CHECK(std::fabs(error) < (slicer.cura ? 0.10 : 0.05));
    ++compared;
  }
  CHECK(compared == 9);  // 3 Cura + 6 PrusaSlicer fixtures carry an estimate
}

// PrusaSlicer's estimate (GCodeProcessor::process_G10/G11 store a vertex and
// no time) leaves firmware retraction out; ours counts what the firmware does
// (RepRapFirmware's defaults here: the file sets no M207). The whole
// difference is that time: without it the two agree within 1 %, once our
// 10 s per G28 (slicers count none) is taken off.
TEST_CASE("on a PrusaSlicer file with firmware retraction ours exceeds PrusaSlicer by the retraction time alone", "[estimator][fixtures]") {
  std::string text = gctest::read_file(gctest::fixture_path("prusa_tshape_0.2_rrf_fwretract.gcode"));
  gctest::SlicerTime slicer = gctest::slicer_time(text);
  REQUIRE(slicer.found);
  auto estimate = [&text](bool firmware_retraction) {
    gcode::EstimatorOptions o;
    o.heat_time = false;
    o.limits.load_profile_text(std::string_view(text).substr(text.find("; prusaslicer_config = begin")));
    if (!firmware_retraction) o.limits.load_profile_text("fw_retract_length = 0\nfw_unretract_extra = 0\n");
    gcode::MemoryLineSplitter lines(text);
    gcode::RawLine raw;
    gcode::MachineState state;
    gcode::Estimator e(o);
    int g10 = 0;
    while (lines.next(raw)) {
      gcode::Line line = gcode::Line::parse(raw.text);
      gcode::Move m = state.apply(line);
      g10 += m.kind == gcode::MoveKind::FirmwareRetract ? 1 : 0;
      e.add(line, m);
    }
    e.finish();
    CHECK(g10 == 115);
    CHECK(e.limits().firmware == gcode::Firmware::RepRapFirmware);
    return std::make_pair(e.elapsed(), e.breakdown());
  };
  auto [with, with_parts] = estimate(true);
  auto [without, without_parts] = estimate(false);
  CHECK(without_parts.retract == 0);  // PrusaSlicer writes no E-only retraction here
  // The difference is the retraction time, and a little more for the stops around each.
  CHECK(with - without >= with_parts.retract);
  CHECK(with - without == Approx(with_parts.retract).epsilon(0.03));
  // 115 retractions and 114 recoveries of 2 mm at 1000 mm/min: at least 0.12 s each.
  CHECK(with_parts.retract > 229 * 0.12);
  double rest = without - without_parts.home;
  INFO("slicer " << slicer.seconds << " s, ours " << with << " s, ours without firmware retraction and homing " << rest);
  CHECK(std::fabs(rest - slicer.seconds) / slicer.seconds < 0.01);
  CHECK(with > slicer.seconds * 1.05);
}
