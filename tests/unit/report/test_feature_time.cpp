// Time by feature (report/feature_time.hpp): each move of the layers at its
// nominal speed under what it is, acceleration apart; the parts add up to
// the layers' time of the same estimate.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "gcode/report/feature_time.hpp"
#include "gcode/report/layer_time.hpp"
#include "test_support.hpp"

namespace test_report_feature_time {

// Start code with a wait, two layers: a 20 mm outer wall at 20 mm/s, a 30 mm
// fill at 60 mm/s with a square turn, a retraction, travel, a layer change,
// a dwell, the wall again.
const char* kPrint =
    "M83\nG28\nG4 S2\n"
    ";LAYER:0\nG0 Z0.2 F600\n;TYPE:WALL-OUTER\nG1 X20 Y0 E1 F1200\n;TYPE:FILL\nG1 X20 Y15 E1 F3600\n"
    "G1 X5 Y15 E1\nG1 E-1 F2100\nG0 X0 Y0 F6000\nG1 E1 F2100\n"
    ";LAYER:1\nG0 Z0.4 F600\nG4 S1\n;TYPE:WALL-OUTER\nG1 X20 Y0 E1 F1200\n"
    "M84\n";

}  // namespace test_report_feature_time

TEST_CASE("feature time: the parts add up to the layers' time, acceleration apart", "[feature_time]") {
  gcode::LayerTimer layers;
  gcode::FeatureTimer features;
  gctest::run_stages(test_report_feature_time::kPrint, {&layers, &features});
  const gcode::FeatureTimes f = features.times([](int id) { return id == 0 ? "WALL-OUTER" : "FILL"; });  // names: the tracker's
  const gcode::LayerTimes& t = layers.times();
  CHECK(f.layers() == Approx(t.total() - t.start - t.end).margin(1e-9));
  CHECK(f.start == Approx(t.start));
  REQUIRE(f.features.size() == 2);
  CHECK(f.features[0].name == "WALL-OUTER");
  CHECK(f.features[0].seconds == Approx(2 * 20.0 / 20));  // two walls at nominal speed
  CHECK(f.features[1].seconds == Approx(30.0 / 60));
  CHECK(f.walls() == Approx(2.0));
  CHECK(f.other_extrusion() == Approx(0.5));
  CHECK(f.travel == Approx(std::hypot(5.0, 15.0) / 100));
  CHECK(f.layer_change == Approx(2 * 0.2 / 5));  // Z capped at Marlin's 5 mm/s
  CHECK(f.retract == Approx(2 * 1.0 / 25));      // E capped at Marlin's 25 mm/s
  CHECK(f.waits == Approx(1.0));
  CHECK(f.acceleration > 0.01);  // every move here starts and stops
}
