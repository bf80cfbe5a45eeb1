// The speed stage (transform/speed.hpp): exact F at the region's edges, the
// gc-send case (switched on mid-layer, off at the layer's end), rounding on
// exact decimals, caps, the M220 route, marks, and lines it must not edit.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/output_buffer.hpp"
#include "gcode/pipeline/writer.hpp"
#include "gcode/transform/speed.hpp"
#include "speed_check.hpp"
#include "test_support.hpp"

using gcode::SpeedOptions;
using gcode::SpeedStage;

namespace {

SpeedOptions factor_of(double k) {
  SpeedOptions o;
  o.factor = k;
  return o;
}

struct SpeedResult {
  std::string out;
  gcode::SpeedStats stats;
  std::uint64_t warnings = 0;
};

// Runs the stage over `text`; `layers` (if not empty) is the --layers region.
SpeedResult speed(std::string_view text, const SpeedOptions& o, const std::string& layers = {}) {
  gcode::Diagnostics diag("test", -1);
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers);
  gcode::SelectionText region;
  region.layers = layers;
  gcode::LayerSelection where = gcode::LayerSelection::parse(region);
  where.bind(pipeline.tracker());
  SpeedStage stage(o, pipeline.precision(), &diag, layers.empty() ? nullptr : &where);
  pipeline.add(stage);
  std::string out = gctest::run_stages(pipeline, text);
  return {out, stage.stats(), diag.warnings()};
}

// Switches a speed stage on at one input line and off at the next layer
// event: what gc-send does for "rush the rest of this layer".
class Rush : public gcode::Stage {
 public:
  Rush(gcode::Stage& speed, std::uint64_t at_line) : speed_(speed), at_(at_line) {}
  void line(const gcode::TrackedLine& t, gcode::Emitter& out) override {
    if (t.raw.number == at_) {
      speed_.set_enabled(true);
      on_ = true;
    }
    out.pass(t);
  }
  void layer(const gcode::LayerInfo& info, const gcode::MachineState& before, gcode::Emitter& out) override {
    if (on_) speed_.set_enabled(false);
    on_ = false;
    out.layer(info, before);
  }

 private:
  gcode::Stage& speed_;
  std::uint64_t at_;
  bool on_ = false;
};

const char* kTwoLayersSpeed =
    "M83\n"
    "G1 X0 Y0 F1200 ; start\n"
    ";LAYER:0\n"
    "G1 Z0.2\n"
    "G1 X10 E1\n"
    "G1 X20 E1\n"
    ";LAYER:1\n"
    "G1 Z0.4\n"
    "G1 X10 E1\n"
    "G1 F1800\n"
    "G1 X0 E1\n"
    ";LAYER:2\n"
    "G1 Z0.6\n"
    "G1 X10 E1\n"
    "M400\n";

}  // namespace

TEST_CASE("speed scales the inherited F on the first move of the region and restores it on the first move after",
          "[speed]") {
  SpeedResult r = speed(kTwoLayersSpeed, factor_of(1.5), "2");
  CHECK(r.out ==
        "M83\n"
        "G1 X0 Y0 F1200 ; start\n"
        ";LAYER:0\n"
        "G1 Z0.2\n"
        "G1 X10 E1\n"
        "G1 X20 E1\n"
        ";LAYER:1\n"
        "G1 Z0.4\n"                           // a Z move keeps its speed
        "G1 X10 E1 F1800 ; gc-speedup x1.5\n"  // inherited F1200, scaled
        "G1 F1800\n"                           // a line that only sets F is left alone
        "G1 X0 E1 F2700 ; gc-speedup x1.5\n"
        ";LAYER:2\n"
        "G1 Z0.6 F1800 ; gc-speedup restore\n"  // the original modal F, back on the first move
        "G1 X10 E1\n"
        "M400\n");
  CHECK(r.stats.moves_changed == 2);
  CHECK(r.stats.lines_edited == 3);
  CHECK(r.stats.restores == 1);
  CHECK(r.stats.layers == std::vector<int>{2});
  // A factor of 1 changes nothing.
  CHECK(speed(kTwoLayersSpeed, factor_of(1), "2").out == kTwoLayersSpeed);
}

TEST_CASE("speed switched on mid-layer and off at the layer end changes exactly the rest of that layer",
          "[speed][gc-send]") {
  for (const char* name : {"prusa_cube_0.2_mk3s_rel_zhop.gcode", "cura_pegs_0.2_rel_fwretract.gcode",
                           "slic3r_cube_0.2_abs_reprap_skirt.gcode"}) {
    INFO(name);
    std::string text = gctest::read_file(gctest::fixture_path(name));
    gctest::LinePlace place = gctest::places_of(text);
    // A line in the middle of layer 5.
    std::size_t first = 0, last = 0;
    for (std::size_t i = 0; i < place.layer.size(); ++i) {
      if (place.layer[i] != 5) continue;
      if (first == 0) first = i;
      last = i;
    }
    // From the middle of layer 5, the first extruding move without an F word:
    // the F it inherits must be re-emitted, scaled.
    std::vector<gctest::ReplayedMove> moves = gctest::replay_moves(text);
    std::vector<std::string> lines = gctest::split_lines(text);
    std::size_t at = 0;
    for (const gctest::ReplayedMove& m : moves)
      if (m.line_index >= (first + last) / 2 && m.line_index <= last && m.move.extruding &&
          lines[m.line_index].find('F') == std::string::npos) {
        at = m.line_index;
        break;
      }
    REQUIRE(at > 0);
    gcode::LayerMarkers markers;
    gcode::Pipeline pipeline(markers);
    SpeedStage stage(factor_of(3), pipeline.precision());
    stage.set_enabled(false);
    CHECK_FALSE(stage.enabled());
    Rush rush(stage, at + 1);
    pipeline.add(rush);
    pipeline.add(stage);
    std::string out = gctest::run_stages(pipeline, text);
    gctest::SpeedRule rule;
    for (std::size_t i = 0; i < place.layer.size(); ++i) rule.factor.push_back(i >= at && place.layer[i] == 5 ? 3.0 : 0.0);
    gctest::SpeedCheck c = gctest::check_speed(text, out, rule);
    CHECK(c.first_failure() == "");
    CHECK(c.changed > 10);
    CHECK(c.inherited_in == 1);  // the current F re-emitted scaled on the first move
    // Once the original F is back, the stage has switched itself off.
    CHECK_FALSE(stage.enabled());
    CHECK_FALSE(stage.changing());
    CHECK(stage.stats().layers == std::vector<int>{5});
  }
}

TEST_CASE("speed switched off while in step goes off at once and on again starts from the current F", "[speed][gc-send]") {
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers, gcode::PipelineOptions{.layers = false});
  SpeedStage stage(factor_of(2), pipeline.precision());
  std::string out;
  {
    gcode::OutputBuffer buffer(out);
    gcode::GcodeWriter writer(buffer);
    pipeline.add(stage);
    pipeline.add(writer);
    stage.set_enabled(false);
    pipeline.feed("M83\nG1 X0 F600\nG1 X1 E1\n");
    stage.set_enabled(true);
    pipeline.feed("G1 X2 E1\nG1 X3 E1\n");
    CHECK(stage.changing());
    stage.set_enabled(false);
    CHECK(stage.enabled());  // on until the next move has its F back
    pipeline.feed("M117 hello\n");
    CHECK(stage.enabled());
    pipeline.feed("G1 X4 E1\nG1 X5 E1\n");
    CHECK_FALSE(stage.enabled());
    pipeline.finish();
  }
  CHECK(out ==
        "M83\nG1 X0 F600\nG1 X1 E1\n"
        "G1 X2 E1 F1200 ; gc-speedup x2\nG1 X3 E1\n"
        "M117 hello\n"
        "G1 X4 E1 F600 ; gc-speedup restore\nG1 X5 E1\n");
}

TEST_CASE("speed rounds the exact decimal product at the input's F decimals", "[speed][numbers]") {
  // 1001 x 1.15 = 1151.15: F1151.2 at one decimal (doubles give 1151.1499999999999).
  CHECK(speed("M83\nG1 X0 F1001.0\nG1 X10 E1\n", factor_of(1.15)).out ==
        "M83\nG1 X0 F1001.0\nG1 X10 E1 F1151.2 ; gc-speedup x1.15\n");
  // Without decimals in the input: whole numbers, half away from zero.
  CHECK(speed("M83\nG1 X0 F1001\nG1 X10 E1\n", factor_of(1.5)).out ==
        "M83\nG1 X0 F1001\nG1 X10 E1 F1502 ; gc-speedup x1.5\n");
  // A ramp's factor shows four decimals; the F is from the exact factor.
  SpeedOptions ramp;
  ramp.ramp = true;
  ramp.ramp_first = 1;
  ramp.ramp_last = 2;
  ramp.ramp_layers = {1, 2, 3, 4};
  SpeedResult r = speed(";LAYER:0\nM83\nG1 X0 Z0.2 F3000\nG1 X1 E1\n;LAYER:1\nG1 Z0.4\nG1 X2 E1\n", ramp);
  CHECK(r.out == ";LAYER:0\nM83\nG1 X0 Z0.2 F3000\nG1 X1 E1\n;LAYER:1\nG1 Z0.4\nG1 X2 E1 F4000 ; gc-speedup x1.3333\n");
  // Inches: F in inches per minute, with two more decimals.
  SpeedResult inch = speed("G20\nM83\nG1 X0 F10.5\nG1 X1 E0.1\n", factor_of(3));
  CHECK(inch.out == "G20\nM83\nG1 X0 F10.5\nG1 X1 E0.1 F31.5 ; gc-speedup x3\n");
  CHECK(gctest::replay_state(inch.out).feedrate == Approx(31.5 * 25.4));
}

TEST_CASE("speed changes extrusion and arcs but never retractions or wipes or Z moves and travel only when asked",
          "[speed]") {
  const char* text =
      "M83\nG1 X0 Y0 F1200\n"
      "G1 X10 E1\n"           // extrusion
      "G2 X20 Y0 I5 J0 E1\n"  // an extruding arc
      "G1 E-1\n"              // retraction
      "G1 X25 Y0 E-0.5\n"     // wipe: retracting while moving
      "G1 Z0.6\n"             // Z-hop
      "G1 X40 Y10\n"          // travel
      "G1 Z0.2\n"             // back down
      "G1 E1.5\n"             // unretraction
      "G1 X50 E1\n";
  SpeedResult plain = speed(text, factor_of(2));
  CHECK(plain.out ==
        "M83\nG1 X0 Y0 F1200\n"
        "G1 X10 E1 F2400 ; gc-speedup x2\n"
        "G2 X20 Y0 I5 J0 E1\n"
        "G1 E-1 F1200 ; gc-speedup restore\n"
        "G1 X25 Y0 E-0.5\nG1 Z0.6\nG1 X40 Y10\nG1 Z0.2\nG1 E1.5\n"
        "G1 X50 E1 F2400 ; gc-speedup x2\n");
  SpeedOptions travel = factor_of(2);
  travel.travel_factor = 3;
  CHECK(speed(text, travel).out ==
        "M83\nG1 X0 Y0 F1200\n"
        "G1 X10 E1 F2400 ; gc-speedup x2\n"
        "G2 X20 Y0 I5 J0 E1\n"
        "G1 E-1 F1200 ; gc-speedup restore\n"
        "G1 X25 Y0 E-0.5\nG1 Z0.6\n"
        "G1 X40 Y10 F3600 ; gc-speedup x3\n"
        "G1 Z0.2 F1200 ; gc-speedup restore\n"
        "G1 E1.5\n"
        "G1 X50 E1 F2400 ; gc-speedup x2\n");
}

TEST_CASE("speed caps round toward the cap and never turn the change around", "[speed][caps]") {
  // 0.1 mm of filament per mm, 1.75 mm filament: 8 mm3/s is F1995.7...; written F1995.
  SpeedOptions flow = factor_of(3);
  flow.max_flow = 8;
  double cap = 8 * 60 / (0.1 * 3.141592653589793 / 4 * 1.75 * 1.75);
  REQUIRE(std::floor(cap) == 1995);
  SpeedResult r = speed("M83\nG1 X0 F1200\nG1 X10 E1\nG1 X20 E0.5\n", flow);
  CHECK(r.out == "M83\nG1 X0 F1200\nG1 X10 E1 F1995 ; gc-speedup x3 capped\nG1 X20 E0.5 F3600 ; gc-speedup x3\n");
  CHECK(r.stats.capped_flow == 1);
  // Already faster than --max-speed: a speed-up keeps the move's speed.
  SpeedOptions max = factor_of(3);
  max.max_speed = 20;
  SpeedResult kept = speed("M83\nG1 X0 F3000\nG1 X10 E1\n", max);
  CHECK(kept.out == "M83\nG1 X0 F3000\nG1 X10 E1\n");
  CHECK(kept.stats.capped_max_speed == 1);
  CHECK(kept.stats.moves_changed == 0);
  // Slower than --min-speed already: a slow-down keeps it; otherwise rounded up to the floor.
  SpeedOptions min = factor_of(0.5);
  min.min_speed = 12.345;
  CHECK(speed("M83\nG1 X0 F600\nG1 X10 E1\n", min).out == "M83\nG1 X0 F600\nG1 X10 E1\n");
  CHECK(speed("M83\nG1 X0 F1000\nG1 X10 E1\n", min).out == "M83\nG1 X0 F1000\nG1 X10 E1 F741 ; gc-speedup x0.5 capped\n");
  // An absolute speed.
  SpeedOptions fixed;
  fixed.speed = 33.3;
  CHECK(speed("M83\nG1 X0 F1000\nG1 X10 E1\n", fixed).out == "M83\nG1 X0 F1000\nG1 X10 E1 F1998 ; gc-speedup 33.3mm/s\n");
}

TEST_CASE("speed with M220 inserts the factor before the region's first move and the restore after it", "[speed][m220]") {
  SpeedOptions o = factor_of(1.5);
  o.m220 = true;
  SpeedResult r = speed(kTwoLayersSpeed, o, "2");
  CHECK(r.out ==
        "M83\nG1 X0 Y0 F1200 ; start\n;LAYER:0\nG1 Z0.2\nG1 X10 E1\nG1 X20 E1\n;LAYER:1\n"
        "M220 S150 ; gc-speedup x1.5\n"
        "G1 Z0.4\nG1 X10 E1\nG1 F1800\nG1 X0 E1\n;LAYER:2\n"
        "M220 S100 ; gc-speedup restore\n"
        "G1 Z0.6\nG1 X10 E1\nM400\n");
  // A region to the end: the restore is the last line.
  o.m220_restore = gcode::M220Restore::Backup;
  SpeedResult end = speed(kTwoLayersSpeed, o, "3-");
  const std::string tail = "M400\nM220 R ; gc-speedup restore\n";
  CHECK(end.out.substr(end.out.size() - tail.size()) == tail);
  CHECK(end.out.find(";LAYER:2\nM220 B ; gc-speedup x1.5\nM220 S150 ; gc-speedup x1.5\nG1 Z0.6\n") != std::string::npos);
  CHECK(end.stats.m220_lines == 3);
}

TEST_CASE("speed refuses lines an earlier run marked unless forced and ignores its restores", "[speed][marks]") {
  std::string marked = "M83\nG1 X0 F600\nG1 X1 E1 F1200 ; gc-speedup x2\nG1 X2 E1\n";
  CHECK_THROWS_WITH(speed(marked, factor_of(2)), Catch::Contains("line 3: already changed by gc-speedup"));
  SpeedOptions force = factor_of(2);
  force.force = true;
  CHECK(speed(marked, force).out == "M83\nG1 X0 F600\nG1 X1 E1 F2400 ; gc-speedup x2 ; gc-speedup x2\nG1 X2 E1\n");
  CHECK_NOTHROW(speed("M83\nG1 X0 F600 ; gc-speedup restore\nG1 X1 E1\n", factor_of(2)));
  CHECK_THROWS(speed("M83\nG1 X0 F600\nG1 X1 E1 F900 ; gc-speedup restore ; gc-speedup x1.5\n", factor_of(2)));
  // Outside the region a mark is no concern; without a mark nothing is written or checked.
  CHECK_NOTHROW(speed(";LAYER:0\nM83\nG1 Z0.2 F600 ; gc-speedup x2\nG1 X1 E1\n;LAYER:1\nG1 Z0.4\nG1 X2 E1\n", factor_of(2), "2"));
  SpeedOptions unmarked = factor_of(2);
  unmarked.mark.clear();
  CHECK(speed(marked, unmarked).out == "M83\nG1 X0 F600\nG1 X1 E1 F2400 ; gc-speedup x2\nG1 X2 E1\n");
}

TEST_CASE("speed leaves numbered and checksummed lines and a bare F alone with one warning", "[speed]") {
  SpeedResult r = speed("M83\nG1 X0 F600\nN10 G1 X1 E1*99\nG1 X2 E1 F\nG1 X3 E1\n", factor_of(2));
  CHECK(r.out == "M83\nG1 X0 F600\nN10 G1 X1 E1*99\nG1 X2 E1 F\nG1 X3 E1 F1200 ; gc-speedup x2\n");
  CHECK(r.stats.left_alone == 2);
  CHECK(r.warnings == 1);
}

TEST_CASE("speed options that make no sense are refused", "[speed][usage]") {
  auto refused = [](auto change) {
    SpeedOptions o;
    change(o);
    return o;
  };
  CHECK_THROWS_WITH(refused([](SpeedOptions& o) { o.factor = 0; }).validate(), Catch::Contains("--factor"));
  CHECK_THROWS_WITH(refused([](SpeedOptions& o) { o.factor = NAN; }).validate(), Catch::Contains("--factor"));
  CHECK_THROWS_WITH(refused([](SpeedOptions& o) { o.speed = -1; }).validate(), Catch::Contains("--speed"));
  CHECK_THROWS_WITH(refused([](SpeedOptions& o) { o.speed = 10, o.ramp = true; }).validate(), Catch::Contains("one change"));
  CHECK_THROWS_WITH(refused([](SpeedOptions& o) { o.ramp = true, o.ramp_last = 0; }).validate(), Catch::Contains("--ramp"));
  CHECK_THROWS_WITH(refused([](SpeedOptions& o) { o.min_speed = 50, o.max_speed = 40; }).validate(),
                    Catch::Contains("--min-speed 50 is above --max-speed 40"));
  CHECK_THROWS_WITH(refused([](SpeedOptions& o) { o.m220 = true, o.max_flow = 5; }).validate(), Catch::Contains("--m220"));
  CHECK_THROWS_WITH(refused([](SpeedOptions& o) { o.m220 = true, o.travel = true; }).validate(), Catch::Contains("--m220"));
  CHECK_THROWS_WITH(refused([](SpeedOptions& o) { o.m220 = true, o.factor = 0.001; }).validate(), Catch::Contains("--m220"));
  CHECK_THROWS_WITH(refused([](SpeedOptions& o) { o.filament_diameter = 0; }).validate(), Catch::Contains("--filament"));
  CHECK_NOTHROW(SpeedOptions().validate());
}

TEST_CASE("speed: M220 B/R only where the file names Marlin 2, else S100", "[speed][m220]") {
  CHECK(gcode::m220_restore_for_flavor("marlin2") == gcode::M220Restore::Backup);
  CHECK(gcode::m220_restore_for_flavor("Marlin2") == gcode::M220Restore::Backup);
  // Marlin 1.x, Klipper, RepRapFirmware ignore B/R: the printer would stay at the changed speed.
  for (const char* flavor : {"marlin", "klipper", "reprapfirmware", ""})
    CHECK(gcode::m220_restore_for_flavor(flavor) == gcode::M220Restore::Reset);
}
