// Pauses at layer boundaries (transform/pause_stage.hpp): which layers the
// triggers pick (before, after, every N, above a height: once each), what
// verify() refuses, the block placed after the previous layer's last line
// with {layer} and {z} expanded, the dry run, the table.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/transform/pause_stage.hpp"
#include "test_support.hpp"

using gcode::LayerRange;
using gcode::PauseTriggers;

namespace {

const char* kThree =
    "M82\nG28\nG92 E0\n"
    ";LAYER_CHANGE\n;Z:0.2\nG1 Z0.2 F600\nG1 X10 Y10 E1 F1200\n"
    ";LAYER_CHANGE\n;Z:0.4\nG1 Z0.4\nG1 X20 Y10 E2\n"
    ";LAYER_CHANGE\n;Z:0.6\nG1 Z0.6\nG1 X20 Y20 E3\n"
    "M104 S0\n";

std::vector<int> fired(PauseTriggers& t, int layers, double height = 0.2) {
  std::vector<int> out;
  for (int i = 1; i <= layers; ++i)
    if (t.at_layer(i, height * i)) out.push_back(i);
  return out;
}

std::string verify_error(const PauseTriggers& t, int layers, double top) {
  try {
    t.verify(layers, top);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

struct Paused {
  std::string out;
  std::vector<gcode::PlacedPause> pauses;
};

Paused run(PauseTriggers& triggers, gcode::PauseConfig config = {}, bool dry = false) {
  gcode::ParkRules park;
  park.given = true;
  park.x = 5;
  park.y = 200;
  gcode::Diagnostics diag("gc-test", -1);
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers);
  gcode::PauseStage stage(triggers, park, config, pipeline.precision(), diag, "gc-test: ");
  stage.set_dry_run(dry);
  pipeline.add(stage);
  Paused p;
  p.out = gctest::run_stages(pipeline, kThree);
  p.pauses = stage.pauses();
  CHECK(stage.layers() == 3);
  CHECK(stage.top_layer_z() == 0.6);
  return p;
}

}  // namespace

TEST_CASE("pause triggers: before, after and every N", "[pause_stage]") {
  PauseTriggers before;
  before.before = LayerRange::parse("2,4-");
  CHECK(before.any());
  CHECK(fired(before, 5) == std::vector<int>{2, 4, 5});
  PauseTriggers after;
  after.after = LayerRange::parse("1,3");
  CHECK(fired(after, 5) == std::vector<int>{2, 4});
  CHECK_FALSE(after.after_last(5));
  CHECK(after.after_last(3));  // "after layer 3" of a 3-layer file: after the last
  PauseTriggers every;
  every.every = 2;
  CHECK(fired(every, 7) == std::vector<int>{3, 5, 7});
  CHECK_FALSE(PauseTriggers().any());
}

TEST_CASE("pause triggers: a height fires once, at the first layer above it", "[pause_stage]") {
  PauseTriggers t;
  t.heights = {0.4, 0.45};
  // Layers at 0.2, 0.4, 0.6, 0.8: 0.4 itself is not above 0.4.
  CHECK(fired(t, 4) == std::vector<int>{3});
  CHECK(verify_error(t, 4, 0.8) == "no error");
  PauseTriggers high;
  high.heights = {2};
  CHECK(fired(high, 4).empty());
  CHECK(verify_error(high, 4, 0.8) == "--z 2: no layer starts above that height (the top layer is at Z 0.8)");
}

TEST_CASE("pause triggers: verify names what the file does not have", "[pause_stage]") {
  PauseTriggers none;
  CHECK(verify_error(none, 0, 0) == "no layers found: the input is empty or prints nothing");
  PauseTriggers before;
  before.before = LayerRange::parse("2,9");
  fired(before, 3);
  CHECK(verify_error(before, 3, 0.6) == "--before-layer 2,9: no such layer, the file has 3 layers");
  PauseTriggers after;
  after.after = LayerRange::parse("1");
  fired(after, 1);
  CHECK(verify_error(after, 1, 0.2) == "--after-layer 1: no such layer, the file has 1 layer");
  PauseTriggers every;
  every.every = 5;
  fired(every, 3);
  CHECK(verify_error(every, 3, 0.6) == "--every 5: the file has only 3 layers, so no pause");
}

TEST_CASE("pause triggers: a height at or above the print's top is refused at once", "[pause_stage]") {
  PauseTriggers t;
  t.heights = {0.3, 12.5};
  gcode::PrintArea area;
  CHECK_NOTHROW(t.check_heights(area));  // the top is unknown
  area.has_print_top = true;
  area.print_top = 12.5;
  CHECK_THROWS_WITH(t.check_heights(area), "--z 12.5: the print is only 12.5 mm high");
  area.print_top = 12.6;
  CHECK_NOTHROW(t.check_heights(area));
}

TEST_CASE("pause stage: the block ends the previous layer, with {layer} and {z}", "[pause_stage]") {
  PauseTriggers t;
  t.before = LayerRange::parse("2");
  gcode::PauseConfig config;
  config.message = "Paused at layer {layer}, Z {z}";
  Paused p = run(t, config);
  std::size_t at = p.out.find("; gc-test: pause before layer 2 (Z 0.4)\n");
  REQUIRE(at != std::string::npos);
  CHECK(p.out.substr(0, at) == "M82\nG28\nG92 E0\n;LAYER_CHANGE\n;Z:0.2\nG1 Z0.2 F600\nG1 X10 Y10 E1 F1200\n");
  std::size_t end = p.out.find("; gc-test: end\n");
  REQUIRE(end != std::string::npos);
  CHECK(p.out.substr(end) == "; gc-test: end\n;LAYER_CHANGE\n;Z:0.4\nG1 Z0.4\nG1 X20 Y10 E2\n"
                             ";LAYER_CHANGE\n;Z:0.6\nG1 Z0.6\nG1 X20 Y20 E3\nM104 S0\n");
  std::string block = p.out.substr(at, end - at);
  CHECK(block.find("Paused at layer 2, Z 0.4") != std::string::npos);
  CHECK(block.find("{") == std::string::npos);
  CHECK(block.find("; gc-test: resume\n") != std::string::npos);
  CHECK(block.find("X5 Y200") != std::string::npos);  // parked where asked
  REQUIRE(p.pauses.size() == 1);
  CHECK(p.pauses[0].layer == 2);
  CHECK(p.pauses[0].z == 0.4);
  CHECK(p.pauses[0].line == 8);
  CHECK(p.pauses[0].park_x == 5);
  CHECK(p.pauses[0].park_y == 200);
  CHECK(p.pauses[0].park_z == 2.2);
}

TEST_CASE("pause stage: after the last layer the pause comes before the end code", "[pause_stage]") {
  PauseTriggers t;
  t.after = LayerRange::parse("3");
  gcode::PauseConfig config;
  config.message = "at {layer}";
  Paused p = run(t, config);
  std::size_t at = p.out.find("; gc-test: pause after the last layer (Z 0.6)\n");
  REQUIRE(at != std::string::npos);
  CHECK(p.out.substr(0, at).size() == std::string(kThree).find("M104 S0"));
  CHECK(p.out.find("at end") != std::string::npos);
  CHECK(p.out.substr(p.out.size() - 23) == "; gc-test: end\nM104 S0\n");
  REQUIRE(p.pauses.size() == 1);
  CHECK(p.pauses[0].layer == 0);
  CHECK(p.pauses[0].line == 16);
}

TEST_CASE("pause stage: a dry run plans without writing", "[pause_stage]") {
  PauseTriggers t;
  t.every = 1;
  Paused p = run(t, {}, true);
  CHECK(p.out == kThree);
  REQUIRE(p.pauses.size() == 2);
  CHECK(p.pauses[0].layer == 2);
  CHECK(p.pauses[1].layer == 3);
  // Parked 2 mm (the lift) above the highest Z printed.
  CHECK(p.pauses[0].park_z == 2.2);
  CHECK(p.pauses[1].park_z == 2.4);
  CHECK(gcode::pause_table(p.pauses) ==
        "# layer\tz\tline\tpark\n"
        "2\t0.4\t8\tX5 Y200 Z2.2\n"
        "3\t0.6\t12\tX5 Y200 Z2.4\n");
  CHECK(gcode::pause_table({}) == "# layer\tz\tline\tpark\n");
  CHECK(gcode::pause_table({{0, 1.25, 40, 0.5, 1, 3}}) == "# layer\tz\tline\tpark\nend\t1.25\t40\tX0.5 Y1 Z3\n");
}

TEST_CASE("pause stage: without --park or a bed size the stage refuses to start", "[pause_stage]") {
  PauseTriggers t;
  gcode::Diagnostics diag("gc-test", -1);
  gcode::Precision p;
  CHECK_THROWS_AS(gcode::PauseStage(t, gcode::ParkRules{}, gcode::PauseConfig{}, p, diag, ""), std::runtime_error);
}
