// pause_sequence.hpp: the blocks are replayed through MachineState; what the
// file's next line relies on must come back exactly, and what the options
// ask for (and nothing else) must happen in between.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/transform/pause_sequence.hpp"
#include "test_support.hpp"

using namespace gcode;

namespace {

MachineState state_after(const std::string& text) { return gctest::replay_state(text); }

struct PauseReplay {
  MachineState end;
  double net = 0;
  double lowest_xy_travel_z = 1e9;  // lowest Z at which the head moved in XY
  std::vector<std::string> lines;
};

PauseReplay replay(const MachineState& start, const PauseBlock& block) {
  PauseReplay r;
  r.end = start;
  double before = start.filament_total;
  for (const auto* half : {&block.pause, &block.resume}) {
    for (const std::string& l : *half) {
      r.lines.push_back(l);
      Move m = r.end.apply(Line::parse(l));
      if (m.xy_length > 0) r.lowest_xy_travel_z = std::min(r.lowest_xy_travel_z, m.end[kZ]);
    }
  }
  r.net = r.end.filament_total - before;
  return r;
}

void require_restored(const MachineState& a, const MachineState& b) {
  CHECK(a.position[kX] == b.position[kX]);
  CHECK(a.position[kY] == b.position[kY]);
  CHECK(a.position[kZ] == b.position[kZ]);
  // Relative E: the running sum of E words, exact up to float noise.
  if (b.relative_e) {
    CHECK(a.position[kE] == Approx(b.position[kE]).margin(1e-12));
  } else {
    CHECK(a.position[kE] == b.position[kE]);
  }
  CHECK(a.relative_e == b.relative_e);
  CHECK(a.relative_xyz == b.relative_xyz);
  CHECK(a.feedrate == b.feedrate);
  CHECK(a.firmware_retracted == b.firmware_retracted);
  CHECK(a.hotend_target == b.hotend_target);
}

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

PauseConfig park_at(double x, double y) {
  PauseConfig c;
  c.park_x = x;
  c.park_y = y;
  return c;
}

}  // namespace

TEST_CASE("pause: absolute E retracts, parks, returns and restores the E coordinate", "[pause]") {
  MachineState s = state_after("G28\nM104 S205\nM82\nG1 X10 Y20 Z0.3 F1500\nG1 X20 E5.12345\n");
  PauseBlock b = build_pause(PausePoint{s}, park_at(110, 210));
  CHECK(b.pause.front() == "G1 E3.12345 F2100");
  CHECK(b.pause.back() == "M0");
  CHECK(has(b.pause, "G1 Z2.3 F600"));
  CHECK(has(b.pause, "G1 X110 Y210 F3600"));
  CHECK(has(b.resume, "G1 X20 Y20 F3600"));
  CHECK(has(b.resume, "G1 Z0.3 F600"));
  CHECK(has(b.resume, "G92 E5.12345"));
  CHECK(b.resume.back() == "G1 F1500");
  PauseReplay r = replay(s, b);
  require_restored(r.end, s);
  CHECK(r.net == 0);
  CHECK(r.lowest_xy_travel_z == Approx(2.3));
}

TEST_CASE("pause: relative E stays relative (Cura #5130) and needs no G92", "[pause]") {
  MachineState s = state_after("G28\nM83\nG1 X10 Y20 Z0.3 F1500\nG1 X20 E0.5\n");
  PauseBlock b = build_pause(PausePoint{s}, park_at(110, 210));
  CHECK(b.pause.front() == "G1 E-2 F2100");
  CHECK_FALSE(has(b.pause, "M82"));
  CHECK_FALSE(has(b.resume, "M82"));
  CHECK(has(b.resume, "G1 E2 F2100"));
  CHECK(has(b.resume, "M83"));
  for (const std::string& l : b.resume) CHECK(l.rfind("G92", 0) != 0);
  require_restored(replay(s, b).end, s);
}

TEST_CASE("pause: a G91 file gets G90 then M83 again (Marlin couples E to G90), and G91 back", "[pause]") {
  MachineState s = state_after("G28\nG1 X10 Y20 Z0.3 F1500\nG91\nG1 X1 E0.2\n");
  REQUIRE(s.relative_xyz);
  REQUIRE(s.relative_e);
  PauseBlock b = build_pause(PausePoint{s}, park_at(110, 210));
  REQUIRE(b.pause.size() > 2);
  CHECK(b.pause[0] == "G90");
  CHECK(b.pause[1] == "M83");
  CHECK(has(b.resume, "G91"));
  // The E mode comes after the G91 that would otherwise decide it.
  auto g91 = std::find(b.resume.begin(), b.resume.end(), "G91");
  auto m83 = std::find(b.resume.begin(), b.resume.end(), "M83");
  CHECK(g91 < m83);
  // G91 + M82: E absolute while XYZ is relative.
  MachineState t = state_after("G28\nG1 X10 Y20 Z0.3 F1500\nG91\nM82\nG1 X1 E5\n");
  PauseBlock c = build_pause(PausePoint{t}, park_at(110, 210));
  CHECK(c.pause[1] == "M82");
  require_restored(replay(t, c).end, t);
  require_restored(replay(s, b).end, s);
}

TEST_CASE("pause: firmware retraction uses G10/G11, never a second G10", "[pause]") {
  MachineState s = state_after("G28\nM83\nG1 X10 Y20 Z0.3 F1500\nG10\nG11\nG1 X20 E0.5\n");
  REQUIRE(s.uses_firmware_retraction);
  PauseBlock b = build_pause(PausePoint{s}, park_at(110, 210));
  CHECK(b.pause.front() == "G10");
  CHECK(has(b.resume, "G11"));
  for (const std::string& l : b.pause) CHECK(l.find(" E") == std::string::npos);
  require_restored(replay(s, b).end, s);

  MachineState retracted = state_after("G28\nM83\nG1 X10 Y20 Z0.3 F1500\nG1 X20 E0.5\nG10\n");
  PauseBlock c = build_pause(PausePoint{retracted}, park_at(110, 210));
  CHECK_FALSE(has(c.pause, "G10"));
  CHECK_FALSE(has(c.resume, "G11"));
  require_restored(replay(retracted, c).end, retracted);
}

TEST_CASE("pause: a file that already retracted is not retracted again", "[pause]") {
  std::string text = "G28\nM82\nG1 X10 Y20 Z0.3 F1500\nG1 X20 E5\nG1 E3 F2400\n";
  RetractionTracker tracker;
  MachineState s;
  for (const std::string& l : gctest::split_lines(text)) {
    std::string line = l.substr(0, l.size() - 1);
    tracker.observe(s.apply(Line::parse(line)));
  }
  CHECK(tracker.pending() == 2);
  PauseConfig c = park_at(110, 210);
  c.purge = 10;
  PauseBlock b = build_pause(PausePoint{s, tracker.pending()}, c);
  for (const std::string& l : b.pause) CHECK(l.find(" E") == std::string::npos);
  // The purge pushes the file's 2 mm back first and takes them again after.
  CHECK(has(b.resume, "G1 E5 F2100"));
  CHECK(has(b.resume, "G1 E15 F180"));
  CHECK(has(b.resume, "G1 E13 F2100"));
  PauseReplay r = replay(s, b);
  require_restored(r.end, s);
  CHECK(r.net == Approx(10).margin(1e-12));
}

TEST_CASE("pause: unload, reload, purge and prime push exactly their sum, in chunks of at most 150 mm", "[pause]") {
  for (const char* mode : {"M82", "M83"}) {
    MachineState s = state_after(std::string("G28\nM104 S210\n") + mode + "\nG1 X10 Y20 Z5 F1500\nG1 X20 E12.5\n");
    PauseConfig c = park_at(110, 210);
    c.unload = 420;
    c.reload = 400.5;
    c.purge = 35;
    c.prime = 0.25;
    c.standby = true;
    c.standby_temp = 150;
    PauseBlock b = build_pause(PausePoint{s}, c);
    MachineState m = s;
    int e_moves = 0;
    for (const auto* half : {&b.pause, &b.resume})
      for (const std::string& l : *half) {
        Move mv = m.apply(Line::parse(l));
        if (mv.filament != 0) {
          ++e_moves;
          CHECK(std::fabs(mv.filament) <= kMaxExtrudeChunk + 1e-9);
        }
      }
    CHECK(e_moves >= 3 + 3 + 4);
    PauseReplay r = replay(s, b);
    INFO(mode);
    CHECK(r.net == Approx(-420 + 400.5 + 35 + 0.25).margin(1e-9));
    CHECK(b.net_filament == Approx(r.net).margin(1e-12));
    require_restored(r.end, s);
    // Unload while hot, before the standby temperature; heat before reloading.
    auto at = [](const std::vector<std::string>& v, const std::string& prefix) {
      for (std::size_t i = 0; i < v.size(); ++i)
        if (v[i].rfind(prefix, 0) == 0) return static_cast<long>(i);
      return -1L;
    };
    CHECK(at(b.pause, "M104 S150") > at(b.pause, "G1 X110"));
    CHECK(at(b.resume, "M109 S210") == 0);
  }
}

TEST_CASE("pause: the lift is capped at the printer's height and raised to the minimum park Z", "[pause]") {
  MachineState s = state_after("G28\nG1 X10 Y20 Z199 F1500\nG1 X20 E1\n");
  PauseConfig c = park_at(110, 210);
  c.max_z = 200;
  PauseBlock b = build_pause(PausePoint{s}, c);
  CHECK(b.park_z == 200);
  CHECK(has(b.pause, "G1 Z200 F600"));
  c.max_z = 0;
  c.min_park_z = 250;
  b = build_pause(PausePoint{s}, c);
  CHECK(b.safe_z == 201);
  CHECK(b.park_z == 250);
  // Down to the safe height at the park position, then across, then down.
  CHECK(has(b.resume, "G1 Z201 F600"));
  PauseReplay r = replay(s, b);
  CHECK(r.lowest_xy_travel_z == 201);
  require_restored(r.end, s);
}

TEST_CASE("pause: the head travels above everything printed, and returns to a Z-hop height exactly", "[pause]") {
  // The file paused while hopped: 0.6 is what its next lines assume.
  MachineState s = state_after("G28\nG1 X10 Y20 Z0.2 F1500\nG1 X20 E1\nG1 Z0.6\n");
  PauseBlock b = build_pause(PausePoint{s, 0, 0.2}, park_at(110, 210));
  CHECK(has(b.resume, "G1 Z0.6 F600"));
  require_restored(replay(s, b).end, s);
  // Printed up to 10 mm, now lower (an odd file): lift from the top.
  b = build_pause(PausePoint{s, 0, 10}, park_at(110, 210));
  CHECK(b.safe_z == 12);
}

TEST_CASE("pause: coordinates come back exactly even when they are not short decimals", "[pause]") {
  MachineState s = state_after("G28\nG1 X10 Y20 Z0.3 F1500\nG91\nG1 X0.1\nG1 X0.2\nG1 Z0.1\nG90\nG1 X20.000001 E1\n");
  MachineState t = state_after("G28\nG1 X10 Y0 Z0.3 F1500\nG91\nG1 Y0.1\nG1 Y0.2\nG1 Z0.1\nG1 Z0.2\nG90\n");
  REQUIRE(t.position[kY] == 0.3);  // 0.1 + 0.2 is held as the exact decimal, not binary 0.30000000000000004
  for (const MachineState* st : {&s, &t}) require_restored(replay(*st, build_pause(PausePoint{*st}, park_at(1, 2))).end, *st);
}

TEST_CASE("pause: temperatures per tool, and a clear error when there is none to restore", "[pause]") {
  MachineState s = state_after("G28\nM104 T0 S210\nM104 T1 S230\nT1\nG1 X10 Y20 Z0.3 F1500\nG1 X20 E1\n");
  PauseConfig c = park_at(110, 210);
  c.standby = true;
  c.standby_temp = 150;
  PauseBlock b = build_pause(PausePoint{s}, c);
  CHECK(has(b.pause, "M104 T0 S150"));
  CHECK(has(b.pause, "M104 T1 S150"));
  CHECK(has(b.resume, "M109 T0 S210"));
  CHECK(has(b.resume, "M109 T1 S230"));
  c.wait_for_heat = false;
  b = build_pause(PausePoint{s}, c);
  CHECK(has(b.resume, "M104 T1 S230"));
  // A standby above the target waits for cooling with R.
  MachineState one = state_after("G28\nM104 S200\nG1 X10 Y20 Z0.3 F1500\n");
  c.wait_for_heat = true;
  c.standby_temp = 240;
  b = build_pause(PausePoint{one}, c);
  CHECK(has(b.resume, "M109 R200"));
  // Temperatures set by a start macro are invisible: ask for one.
  MachineState none = state_after("G28\nPRINT_START EXTRUDER=215\nG1 X10 Y20 Z0.3 F1500\n");
  CHECK_THROWS_WITH(build_pause(PausePoint{none}, c), Catch::Contains("resume temperature"));
  c.resume_temp = 215;
  c.standby_temp = 150;
  b = build_pause(PausePoint{none}, c);
  CHECK(has(b.resume, "M109 S215"));
}

TEST_CASE("pause: a state that cannot be resumed exactly is refused", "[pause]") {
  MachineState unknown = state_after("M82\nG1 X10 E1\n");
  CHECK_THROWS_WITH(build_pause(PausePoint{unknown}, park_at(1, 2)), Catch::Contains("not known"));
  MachineState inches = state_after("G28\nG20\nG1 X1 Y1 Z0.1\n");
  CHECK_THROWS_WITH(build_pause(PausePoint{inches}, park_at(1, 2)), Catch::Contains("inches"));
}

TEST_CASE("pause: methods, messages and the user's lines", "[pause]") {
  MachineState s = state_after("G28\nG1 X10 Y20 Z0.3 F1500\n");
  struct Case {
    const char* text;
    PauseMethod method;
    const char* wait;
  };
  const Case cases[] = {
      {"M0", PauseMethod::M0, "M0 hi"},          {"m1", PauseMethod::M1, "M1 hi"},
      {"M25", PauseMethod::M25, "M25"},          {"M125", PauseMethod::M125, "M125"},
      {"M226", PauseMethod::M226, "M226"},       {"M600", PauseMethod::M600, "M600"},
      {"M601", PauseMethod::M601, "M601"},       {"@pause", PauseMethod::HostPause, "@pause"},
      {"PAUSE", PauseMethod::Klipper, "PAUSE"},  {"G4", PauseMethod::Dwell, "G4 S12.5"},
      {"custom:M300\nM0 x", PauseMethod::Custom, "M0 x"},
  };
  for (const Case& k : cases) {
    PauseConfig c = park_at(1, 2);
    std::string custom;
    REQUIRE(parse_pause_method(k.text, c.method, custom));
    CHECK(c.method == k.method);
    c.custom_wait = custom;
    c.message = "hi";
    c.dwell_seconds = 12.5;
    c.before_wait = "M117 before";
    c.after_wait = "M117 after\r\nG4 S1\n";
    PauseBlock b = build_pause(PausePoint{s}, c);
    INFO(k.text);
    CHECK(b.pause.back() == k.wait);
    CHECK(b.resume[0] == "M117 after");
    CHECK(b.resume[1] == "G4 S1");
    CHECK(has(b.pause, "M117 before"));
    // M0/M1 carry the message; others show it with M117.
    bool on_wait = k.method == PauseMethod::M0 || k.method == PauseMethod::M1;
    CHECK(has(b.pause, "M117 hi") == !on_wait);
  }
  PauseMethod m;
  std::string t;
  CHECK_FALSE(parse_pause_method("M2", m, t));
  CHECK_FALSE(parse_pause_method("custom:", m, t));
  REQUIRE(parse_pause_method("none", m, t));
  PauseConfig c = park_at(1, 2);
  c.method = m;
  c.message = "";
  PauseBlock b = build_pause(PausePoint{s}, c);
  CHECK(b.pause.back() == "G1 X1 Y2 F3600");
  c.beep = true;
  c.stepper_hold = 900;
  c.host_message = "paused";
  c.wait_for_moves = true;
  b = build_pause(PausePoint{s}, c);
  CHECK(has(b.pause, "M300 S440 P1000"));
  CHECK(has(b.pause, "M84 S900"));
  CHECK(has(b.pause, "M118 paused"));
  CHECK(has(b.pause, "M400"));
}

TEST_CASE("pause: RetractionTracker follows wipes and resets on extrusion", "[pause]") {
  RetractionTracker t;
  MachineState s = state_after("G28\nM83\nG1 X1 Y1 Z0.2 F1000\n");
  for (const char* l : {"G1 X2 E1", "G1 X3 E-0.3", "G1 X4 E-0.2", "G1 E-0.5"}) t.observe(s.apply(Line::parse(l)));
  CHECK(t.pending() == Approx(1.0));
  t.observe(s.apply(Line::parse("G1 E0.4")));
  CHECK(t.pending() == Approx(0.6));
  t.observe(s.apply(Line::parse("G1 X5 E0.1")));
  CHECK(t.pending() == 0);
}
