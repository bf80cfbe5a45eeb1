// Time by feature (report/feature_time.hpp): each move of the layers at its
// nominal speed under what it is, acceleration apart; the parts add up to
// the layers' time of the same estimate.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/report/feature_time.hpp"
#include "gcode/report/layer_time.hpp"
#include "test_support.hpp"

namespace test_report_feature_time {

// Start code with a wait, two layers: a 20 mm outer wall at 20 mm/s, a 30 mm
// fill at 60 mm/s with a square turn, travel, a retraction, a layer change.
const char* kPrint =
    "G28\nG4 S2\n"
    ";LAYER:0\nG0 Z0.2 F600\n;TYPE:WALL-OUTER\nG1 X20 Y0 E1 F1200\n;TYPE:FILL\nG1 X20 Y15 E1 F3600\n"
    "G1 X5 Y15 E1\nG1 E-1 F2100\nG0 X0 Y0 F6000\nG1 E1 F2100\n"
    ";LAYER:1\nG0 Z0.4 F600\n;TYPE:WALL-OUTER\nG1 X20 Y0 E1 F1200\nG4 S1\n"
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
  CHECK(f.layers() > 0);
}
