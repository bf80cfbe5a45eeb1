// Time per layer (report/layer_time.hpp): the estimator's time booked to the
// start code, each layer and the end code; the parts add up to the whole
// estimate, waits land in the region that has them, the look-ahead is
// booked at the end; the timer passes every line on.
#include <catch2/catch.hpp>

#include <numeric>
#include <string>

#include "gcode/pipeline/pipeline.hpp"
#include "gcode/report/layer_time.hpp"
#include "test_support.hpp"

using gcode::LayerTimer;
using gcode::LayerTimes;

namespace {

// Homing (10 s) and a 5 s dwell in the start code, two layers of one 10 mm
// extrusion at 10 mm/s and a dwell each, a 1 s dwell in the end code
// (everything after the last extrusion).
const char* kTimed =
    "G28\nG4 S5\n"
    ";LAYER:0\nG1 Z0.2 F600\nG1 X10 Y0 E1 F600\nG4 S2\n"
    ";LAYER:1\nG1 Z0.4 F600\nG4 P3000\nG1 X0 Y0 E2 F600\n"
    "G4 S1\nM84\n";

}  // namespace

TEST_CASE("layer time: waits are booked to their region, the parts add up", "[layer_time]") {
  gcode::EstimatorOptions options;
  options.heat_time = false;
  LayerTimer timer(options);
  std::string out = gctest::run_stages(kTimed, {&timer});
  CHECK(out == kTimed);
  const LayerTimes& t = timer.times();
  CHECK(t.start == Approx(15).margin(1e-9));  // G28 at 10 s + G4 S5
  REQUIRE(t.layers.size() == 2);
  // 10 mm at 10 mm/s plus the Z move, with acceleration: a little more than
  // 1 s of motion, plus the dwell.
  CHECK(t.layers[0] - 2 > 1.0);
  CHECK(t.layers[0] - 2 < 1.2);
  CHECK(t.layers[1] - 3 > 1.0);
  CHECK(t.layers[1] - 3 < 1.2);
  CHECK(t.end == Approx(1).margin(1e-9));
  CHECK(t.total() == Approx(timer.estimator().total()).epsilon(1e-12));
  CHECK(t.total() == Approx(t.start + t.layers[0] + t.layers[1] + t.end).epsilon(1e-12));
  CHECK(timer.estimator().queued() == 0);  // finished: nothing left in the look-ahead
}

TEST_CASE("layer time: cumulative time runs to the end of each layer", "[layer_time]") {
  LayerTimes t;
  t.start = 10;
  t.layers = {1, 2, 4};
  t.end = 100;
  CHECK(t.total() == 117);
  CHECK(t.cumulative(0) == 10);
  CHECK(t.cumulative(1) == 11);
  CHECK(t.cumulative(3) == 17);
  CHECK(t.cumulative(9) == 17);  // beyond the last layer: the end code is not in it
  CHECK(t.cumulative(-1) == 10);
  CHECK(LayerTimes().total() == 0);
}

TEST_CASE("layer time: a file without layers is all start code", "[layer_time]") {
  LayerTimer timer;
  gctest::run_stages("G28\nG4 S2\n", {&timer});
  CHECK(timer.times().layers.empty());
  CHECK(timer.times().start == Approx(12).margin(1e-9));
  CHECK(timer.times().end == 0);
}

TEST_CASE("layer time: an empty layer gets a slot of zero", "[layer_time]") {
  // Layer 2 is a marker with nothing printed before the next one.
  LayerTimer timer;
  gctest::run_stages(";LAYER:0\nG1 Z0.2\nG1 X10 E1 F600\n;LAYER:1\n;LAYER:2\nG1 Z0.6\nG1 X0 E2 F600\nG4 S1\n", {&timer});
  const LayerTimes& t = timer.times();
  REQUIRE(t.layers.size() == 3);
  CHECK(t.layers[1] == 0);
  CHECK(t.layers[0] > 1);
  CHECK(t.layers[2] > 1);
}

TEST_CASE("layer time: the change before and after, by layer and in total", "[layer_time]") {
  LayerTimes before, after;
  before.layers = {10, 20, 30};
  after.layers = {10, 10, 15};
  before.end = after.end = 40;
  const std::vector<std::string> lines = gcode::time_change_lines(before, after, {2, 3, 4});
  REQUIRE(lines.size() == 3);  // layer 4 is in neither: left out
  CHECK(lines[0] == "layer 2: 20.0 s -> 10.0 s");
  CHECK(lines[1] == "layer 3: 30.0 s -> 15.0 s");
  CHECK(lines[2] == "estimated print time 0:01:40 -> 0:01:15 (-25.0 %)");
  CHECK(gcode::time_change_lines(LayerTimes{}, LayerTimes{}, {}).back() ==
        "estimated print time 0:00:00 -> 0:00:00 (+0.0 %)");
}
