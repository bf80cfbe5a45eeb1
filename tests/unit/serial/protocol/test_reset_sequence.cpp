// The resume sequence after a printer reset (serial/reset_sequence.hpp):
// replayed through a reset printer's MachineState, it heats the bed then the
// hot end and waits, declares Z before anything moves, lifts off the part
// before homing X and Y (never Z), travels above everything printed, comes
// down to the target, primes what the print retracts, and leaves the printer
// exactly as the target: position, E, modes, F, fan, factors. A delta gets
// the gc-relayer recipe instead. And ResumeTrack, what the sequence needs of
// the print besides its state, on a real slicer file.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/serial/protocol/reset_sequence.hpp"
#include "test_support.hpp"

using gcode::kE;
using gcode::kX;
using gcode::kY;
using gcode::kZ;
using gcode::MachineState;
using gcode::serial::reset_resume_lines;
using gcode::serial::ResetResume;
using gcode::serial::ResumeTrack;
using Lines = std::vector<std::string>;

namespace {


std::string joined(const Lines& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

std::size_t index_of(const Lines& lines, const std::string& prefix) {
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].rfind(prefix, 0) == 0) return i;
  return lines.size();
}

// A mid-print state of a relative-E print with a fan, factors and a z-hop print's habits.
MachineState mid_print() {
  return gctest::replay_state(
      "G28\nM140 S60\nM104 S215\nM190 S60\nM109 S215\nG21\nG90\nM83\nM106 S170\nM220 S90\nM221 S95\n"
      "G1 Z0.2 F720\nG1 X10 Y10 F9000\nG1 X60 Y10 E2.5 F1200\nG1 Z12.4 F720\nG1 X40 Y35 E0.8 F1500\n");
}

}  // namespace

TEST_CASE("reset resume: heat bed then nozzle, declare Z, lift, home X Y only, travel high, descend, prime, restore",
          "[reset_sequence]") {
  ResetResume how;
  how.target = mid_print();
  how.top_z = 12.4;
  how.retracted = 0;
  how.prime = 0.8;
  Lines out = reset_resume_lines(how, gctest::kPrecision, {.lift = 1, .e_feed = 2100});
  INFO(joined(out));
  const std::size_t bed = index_of(out, "M190 S60"), hot = index_of(out, "M109 S215"),
                    declare = index_of(out, "G92 Z12.4"), home = index_of(out, "G28 X Y");
  REQUIRE(bed < out.size());
  REQUIRE(hot < out.size());
  REQUIRE(declare < out.size());
  REQUIRE(home < out.size());
  CHECK(bed < hot);
  CHECK(hot < declare);
  CHECK(declare < home);
  for (const std::string& l : out) {
    CHECK(l.rfind("G28 Z", 0) == std::string::npos);
    CHECK(l != "G28");
  }
  // Nothing moves before the heaters are at their targets; the nozzle is
  // off the part before X and Y are homed.
  MachineState p;
  double lowest_xy = 1e300, extruded = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    gcode::Move m = p.apply(gcode::Line::parse(out[i]));
    if (m.moves_head() || m.filament != 0) CHECK(i > hot);
    if (i == home) CHECK(p.position[kZ] >= 13.4 - 1e-9);
    if (m.xy_length > 0) lowest_xy = std::min(lowest_xy, m.end[kZ]);
    extruded += m.filament;
  }
  CHECK(lowest_xy > 12.4);
  CHECK(extruded == Approx(0.8));  // the prime, at the target
  for (int axis : {kX, kY, kZ, kE}) {
    INFO("axis " << axis);
    CHECK(p.at(axis) == how.target.at(axis));
  }
  CHECK(p.relative_e == how.target.relative_e);
  CHECK(p.relative_xyz == how.target.relative_xyz);
  CHECK(p.feedrate == how.target.feedrate);
  CHECK(p.fan == how.target.fan);
  CHECK(p.speed_factor == 90);
  CHECK(p.flow_factor == 95);
  CHECK(p.hotend_target == how.target.hotend_target);
  CHECK(p.bed_target == 60);
}

TEST_CASE("reset resume: the travel clears a taller part than the nozzle's own height, a retracted target stays so",
          "[reset_sequence]") {
  ResetResume how;
  how.target = gctest::replay_state("G28\nM104 S200\nM82\nG1 X20 Y20 Z0.6 F3000\nG92 E0\nG1 X30 E1.2\nG1 E0.4\n");
  how.top_z = 25;  // another object, printed one at a time, stands 25 mm tall
  how.nozzle_z = 0.8;  // the nozzle stopped a layer higher
  how.retracted = 0.8;
  how.prime = 0.8;
  Lines out = reset_resume_lines(how, gctest::kPrecision);
  INFO(joined(out));
  CHECK(index_of(out, "G92 Z0.8") < out.size());
  CHECK(index_of(out, "M190") == out.size());  // no bed target: no bed line
  MachineState p;
  double lowest_xy = 1e300, extruded = 0;
  for (const std::string& l : out) {
    gcode::Move m = p.apply(gcode::Line::parse(l));
    if (m.xy_length > 0) lowest_xy = std::min(lowest_xy, m.end[kZ]);
    extruded += m.filament;
  }
  CHECK(lowest_xy > 25);
  CHECK(extruded == Approx(0));  // primed by the retraction, which the target still has
  CHECK(p.at(kZ) == how.target.at(kZ));
  CHECK(p.at(kE) == how.target.at(kE));
  CHECK_FALSE(p.relative_e);
}

TEST_CASE("reset resume: refused where it cannot know the way, a delta gets the gc-relayer recipe",
          "[reset_sequence]") {
  ResetResume unknown;
  unknown.target = gctest::replay_state("M104 S200\nG1 X10\n");  // never homed
  CHECK_THROWS_AS(reset_resume_lines(unknown, gctest::kPrecision), std::invalid_argument);
  ResetResume inches;
  inches.target = gctest::replay_state("G28\nG20\nG1 X1 Y1 Z1\n");
  CHECK_THROWS_AS(reset_resume_lines(inches, gctest::kPrecision), std::invalid_argument);
  std::string refusal = gcode::serial::xy_homing_refusal(12.25, "part.gcode");
  CHECK(refusal.find("cannot home X and Y without Z") != std::string::npos);
  CHECK(refusal.find("gc-relayer --resume-from-z <measured Z> part.gcode > resume.gcode") != std::string::npos);
  CHECK(refusal.find("Z 12.25") != std::string::npos);
}

TEST_CASE("reset resume: ResumeTrack on a real print knows its top, its retraction and what is retracted",
          "[reset_sequence]") {
  // PrusaSlicer, relative E, 0.8 mm retractions with z-hop.
  std::string text = gctest::read_file(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode"));
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  MachineState s;
  ResumeTrack track;
  double top = 0, longest = 0, extruded_z = 0;
  bool retracted_at_end = false;
  while (split.next(raw)) {
    gcode::Move m = s.apply(gcode::Line::parse(raw.text));
    track.step(m.filament, m.moves_head(), s.position[kZ], false);
    if (m.filament > 0 && m.moves_head()) {
      top = std::max(top, s.position[kZ]);
      extruded_z = s.position[kZ];
    }
    if (m.retraction()) longest = std::max(longest, -m.filament);
    if (m.filament != 0) retracted_at_end = m.filament < 0;
  }
  CHECK(track.top_z == Approx(top));
  CHECK(track.top_z == Approx(extruded_z));
  CHECK(track.retraction >= longest);
  CHECK(track.retraction > 0);
  CHECK((track.retracted > 0) == retracted_at_end);
  // A line of gc-send's own (a pause's unload) is no retraction to prime.
  ResumeTrack own;
  own.step(-100, false, 10, true);
  CHECK(own.retraction == 0);
  CHECK(own.retracted == 100);
}
