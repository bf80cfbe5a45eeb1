// build_seam (transform/seam.hpp): the lines between two pieces of G-code,
// replayed through MachineState: E continuity, the travel above the print,
// modes, E coordinate and F as the block expects them.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/transform/seam.hpp"
#include "test_support.hpp"

using gcode::Fixed;
using gcode::StreamPoint;

namespace {

// A state reached by running `lines` from power-on.
StreamPoint point(const std::string& lines) {
  StreamPoint p;
  p.state = gctest::replay_state(lines);
  return p;
}

std::string joined(const gcode::Seam& s) {
  std::string t;
  for (const std::string& l : s.lines) t += l + "\n";
  return t;
}

// Replays the seam from `from`: the state after it and what it did.
struct SeamReplay {
  gcode::MachineState after;
  double net = 0;
  double lowest_z = 1e300;
  double travel_z = 1e300;
};
SeamReplay replay(const StreamPoint& from, const gcode::Seam& seam) {
  SeamReplay r;
  r.after = from.state;
  for (const std::string& text : seam.lines) {
    gcode::Move m = r.after.apply(gcode::Line::parse(text));
    r.net += m.filament;
    if (m.moves_head()) r.lowest_z = std::min(r.lowest_z, m.end[gcode::kZ]);
    if (m.xy_length > 0) r.travel_z = std::min(r.travel_z, m.end[gcode::kZ]);
  }
  return r;
}


}  // namespace

TEST_CASE("splice seam: absolute E, retract lift travel down unretract then G92 E and F", "[splice][seam]") {
  StreamPoint from = point("G28\nM82\nG1 X10 Y10 Z1 F1200\nG1 X20 E5.0348\n");
  from.top_z = 1;
  StreamPoint to = point("G28\nM82\nG1 X50 Y60 Z1 F3000\nG92 E12.5\n");
  to.layer_z = 1.2;
  gcode::Seam s = gcode::build_seam(from, to, gcode::SeamOptions{}, gctest::kPrecision, false);
  CHECK(joined(s) ==
        "G1 E4.0348 F2100\n"  // 5.0348 - 1: no binary noise
        "G0 Z2.2 F600\n"
        "G0 X50 Y60 F3000\n"
        "G0 Z1.2 F600\n"
        "G1 E5.0348 F2100\n"
        "G92 E12.5\n"
        "G1 F3000\n");
  SeamReplay r = replay(from, s);
  CHECK(r.net == 0);  // retract and unretract the same amount
  CHECK(r.after.at(gcode::kE) == Fixed::from_decimal(125, 1));
  CHECK(r.after.feedrate == 3000);
  CHECK(r.travel_z == Approx(2.2));
  CHECK(r.lowest_z >= 1);
  CHECK(s.safe_z == Approx(2.2));
}

TEST_CASE("splice seam: a stream already retracted is not retracted again", "[splice][seam]") {
  StreamPoint from = point("G28\nM83\nG1 X10 Y10 Z1 F1200\nG1 E-0.8 F2100\n");
  from.retracted = 0.8;
  from.e_mode_set = true;
  StreamPoint to = point("G28\nM83\nG1 X10 Y10 Z0.8\n");
  to.layer_z = 1.2;
  gcode::Seam s = gcode::build_seam(from, to, gcode::SeamOptions{}, gctest::kPrecision, false);
  CHECK(s.lines.front() == "G0 Z2.2 F600");  // no E move before the lift
  SeamReplay r = replay(from, s);
  CHECK(r.net == Approx(0.8));  // the stream's own retraction is made up: the block starts unretracted
  CHECK(s.net_filament == Approx(0.8));
  // Both sides retracted by the same: nothing pushed.
  to.retracted = 0.8;
  CHECK(replay(from, gcode::build_seam(from, to, gcode::SeamOptions{}, gctest::kPrecision, false)).net == 0);
}

TEST_CASE("splice seam: firmware retraction uses G10 and G11", "[splice][seam]") {
  StreamPoint from = point("G28\nM83\nG1 X10 Y10 Z1 F1200\nG10\nG11\n");
  StreamPoint to = point("G28\nM83\nG1 X20 Y10 Z1\n");
  to.layer_z = 1.2;
  gcode::Seam s = gcode::build_seam(from, to, gcode::SeamOptions{}, gctest::kPrecision, false);
  CHECK(s.lines.front() == "G10");
  CHECK(std::find(s.lines.begin(), s.lines.end(), "G11") != s.lines.end());
  CHECK(replay(from, s).net == 0);
  CHECK_FALSE(replay(from, s).after.firmware_retracted);
}

TEST_CASE("splice seam: relative positioning is left for the travel and restored", "[splice][seam]") {
  StreamPoint from = point("G28\nM83\nG1 X10 Y10 Z1 F1200\nG91\n");
  from.e_mode_set = true;
  StreamPoint to = point("G28\nM83\nG1 X20 Y10 Z1\nG91\n");
  to.layer_z = 1.2;
  gcode::Seam s = gcode::build_seam(from, to, gcode::SeamOptions{}, gctest::kPrecision, false);
  // G90 for the travel; Marlin's G90 makes E absolute, so M83 comes back at once.
  CHECK(s.lines.at(0) == "G90");
  CHECK(s.lines.at(1) == "M83");
  SeamReplay r = replay(from, s);
  CHECK(r.after.relative_xyz);
  CHECK(r.after.relative_e);
  CHECK(r.net == 0);
}

TEST_CASE("splice seam: no E mode of its own unless the sides differ and the block is not rewritten",
          "[splice][seam]") {
  StreamPoint from = point("G28\nG1 X10 Y10 Z1 F1200\nG1 X11 E2\n");  // never set: absolute by default
  StreamPoint to = point("G28\nG1 X20 Y10 Z1\n");
  to.layer_z = 1.2;
  gcode::Seam same = gcode::build_seam(from, to, gcode::SeamOptions{}, gctest::kPrecision, false);
  for (const std::string& l : same.lines) CHECK((l != "M82" && l != "M83"));
  StreamPoint rel = point("G28\nM83\nG1 X20 Y10 Z1\n");
  rel.layer_z = 1.2;
  gcode::Seam converted = gcode::build_seam(from, rel, gcode::SeamOptions{}, gctest::kPrecision, true);
  CHECK(converted.e_mode_differs);
  CHECK_FALSE(converted.relative_e);
  for (const std::string& l : converted.lines) CHECK((l != "M82" && l != "M83"));
  gcode::Seam switched = gcode::build_seam(from, rel, gcode::SeamOptions{}, gctest::kPrecision, false);
  CHECK(std::find(switched.lines.begin(), switched.lines.end(), "M83") != switched.lines.end());
  CHECK(replay(from, switched).after.relative_e);
}

TEST_CASE("splice seam: lifts above the highest Z printed and never above the printer", "[splice][seam]") {
  StreamPoint from = point("G28\nG1 X10 Y10 Z1 F1200\n");
  from.top_z = 7.5;  // a taller part printed beside (or before a skip)
  StreamPoint to = point("G28\nG1 X20 Y10 Z1\n");
  to.layer_z = 1.2;
  gcode::SeamOptions o;
  o.lift = 2;
  gcode::Seam s = gcode::build_seam(from, to, o, gctest::kPrecision, false);
  CHECK(s.safe_z == Approx(9.5));
  CHECK(replay(from, s).travel_z == Approx(9.5));
  o.max_z = 8;
  CHECK(gcode::build_seam(from, to, o, gctest::kPrecision, false).safe_z == Approx(8));
}

TEST_CASE("splice seam: the tool and settings change while the nozzle is clear", "[splice][seam]") {
  StreamPoint from = point("G28\nM104 S215\nG1 X10 Y10 Z1 F1200\n");
  from.settings.observe(gcode::Line::parse("M104 S215"), 0);
  StreamPoint to = point("G28\nT1\nG1 X20 Y10 Z1\n");
  to.settings.observe(gcode::Line::parse("M104 T1 S230"), 1);
  to.layer_z = 1.2;
  gcode::Seam s = gcode::build_seam(from, to, gcode::SeamOptions{}, gctest::kPrecision, false);
  auto at = [&](const std::string& l) { return std::find(s.lines.begin(), s.lines.end(), l) - s.lines.begin(); };
  CHECK(at("G0 Z2.2 F600") < at("T1"));
  CHECK(at("T1") < at("M109 S230"));
  CHECK(at("M109 S230") < at("G0 X20 Y10 F3000"));
}

TEST_CASE("splice seam: refuses an unknown position and inches", "[splice][seam]") {
  StreamPoint unknown;
  StreamPoint to = point("G28\nG1 X20 Y10 Z1\n");
  CHECK_THROWS_AS(gcode::build_seam(unknown, to, gcode::SeamOptions{}, gctest::kPrecision, false), std::invalid_argument);
  StreamPoint inches = point("G28\nG20\nG1 X1 Y1 Z1\n");
  CHECK_THROWS_AS(gcode::build_seam(inches, to, gcode::SeamOptions{}, gctest::kPrecision, false), std::invalid_argument);
  gcode::SeamOptions bad;
  bad.travel_speed = 0;
  CHECK_THROWS_AS(bad.validate(), std::invalid_argument);
}
