// Leaving objects out (objects/object_excluder.hpp with objects/catch_up.hpp):
// the kept objects' lines byte for byte; a left-out block's motion dropped
// and its G92 kept; before the next kept line only what it depends on (Z
// before a travel, the retraction before a travel the input makes
// retracted, G92 E where absolute E differs); an object switched off in the
// middle of its block (gc-send's cancel) stops there.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "fn_stage.hpp"
#include "gcode/objects/object_excluder.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "test_support.hpp"

namespace test_object_excluder {

// Two objects, absolute E, PrusaSlicer's labels: A, then B (with a G92 E0
// inside), then A again.
const char* const kExcludePlate =
    "M82\n"
    "G90\n"
    "G92 E0\n"
    ";LAYER_CHANGE\n"
    ";Z:0.2\n"
    "G1 Z0.2 F600\n"
    "; printing object A id:0 copy 0\n"
    "G1 X0 Y0 F6000\n"
    "G1 E1 F2400\n"
    "G1 X10 Y0 E2 F1200\n"
    "G1 X10 Y10 E3\n"
    "G1 E2 F2400\n"
    "G1 Z0.6 F600\n"
    "; stop printing object A id:0 copy 0\n"
    "; printing object B id:1 copy 0\n"
    "G1 X50 Y50 F6000\n"
    "G1 Z0.2 F600\n"
    "G1 E3 F2400\n"
    "G1 X60 Y50 E4 F1200\n"
    "G92 E0\n"
    "G1 X60 Y60 E1\n"
    "G1 E0 F2400\n"
    "; stop printing object B id:1 copy 0\n"
    "; printing object A id:0 copy 0\n"
    "G1 X10 Y10 F6000\n"
    "G1 E1 F2400\n"
    "G1 X0 Y10 E2 F1200\n"
    "; stop printing object A id:0 copy 0\n"
    "M104 S0\n";

// `plate` through an excluder that leaves object `object` out from the start.
std::string without(const char* plate, int object) {
  gcode::LayerMarkers markers;
  gcode::Pipeline p(markers);
  gcode::ObjectExcluder excluder(p.precision());
  excluder.exclude(object);
  p.add(excluder);
  return gctest::run_stages(p, plate);
}

}  // namespace test_object_excluder

using namespace test_object_excluder;

TEST_CASE("object excluder: a left-out block's moves go, its G92 stays, and the travel to the next object is lowered first",
          "[object_excluder]") {
  gcode::LayerMarkers markers;
  gcode::Pipeline p(markers);
  gcode::ObjectExcluder excluder(p.precision());
  excluder.exclude(1);
  p.add(excluder);
  const std::string out = gctest::run_stages(p, kExcludePlate);
  CHECK(out ==
        "M82\nG90\nG92 E0\n;LAYER_CHANGE\n;Z:0.2\nG1 Z0.2 F600\n"
        "; printing object A id:0 copy 0\nG1 X0 Y0 F6000\nG1 E1 F2400\nG1 X10 Y0 E2 F1200\nG1 X10 Y10 E3\nG1 E2 F2400\nG1 Z0.6 F600\n"
        "; stop printing object A id:0 copy 0\n; printing object B id:1 copy 0\nG92 E0\n; stop printing object B id:1 copy 0\n"
        "; printing object A id:0 copy 0\nG0 Z0.2 F600\nG1 X10 Y10 F6000\nG1 E1 F2400\nG1 X0 Y10 E2 F1200\n"
        "; stop printing object A id:0 copy 0\nM104 S0\n");
  CHECK(excluder.dropped_extrusions() == 2);
  CHECK(excluder.dropped_lines() == 6);
}

TEST_CASE("object excluder: switched off in the middle of its block, the object stops there and the next one is primed as in the input",
          "[object_excluder]") {
  gcode::LayerMarkers markers;
  gcode::Pipeline p(markers);
  gcode::ObjectExcluder excluder(p.precision());
  // gc-send's cancel: the decision comes at the block's first extrusion.
  gctest::FnStage cancel([&](const gcode::TrackedLine& t, gcode::Emitter& out) {
    if (t.raw.text == "G1 X60 Y50 E4 F1200") excluder.exclude(excluder.current());
    out.pass(t);
  });
  p.add(cancel);
  p.add(excluder);
  const std::string out = gctest::run_stages(p, kExcludePlate);
  // B's travel, lowering and unretraction went out; from its first
  // extrusion on nothing of it. The input travels to A retracted 1 mm: so
  // does the output, and G92 E puts absolute E back before A's unretraction.
  const std::string tail = out.substr(out.find("G1 E3 F2400\n"));
  CHECK(tail ==
        "G1 E3 F2400\nG92 E0\n; stop printing object B id:1 copy 0\n; printing object A id:0 copy 0\n"
        "G1 E-1 F2100\nG1 X10 Y10 F6000\nG92 E0\nG1 E1 F2400\nG1 X0 Y10 E2 F1200\n"
        "; stop printing object A id:0 copy 0\nM104 S0\n");
  CHECK(excluder.excluded(1));
  CHECK_FALSE(excluder.excluded(0));
}

TEST_CASE("object excluder: the nozzle a left-out block left retracted is primed at the next extrusion, not before the travel",
          "[object_excluder]") {
  const char* const plate =
      "G90\nM83\n;LAYER_CHANGE\n;Z:0.2\nG1 Z0.2 F600\n"
      "; printing object A id:0 copy 0\nG1 X0 Y0 F6000\nG1 X10 Y0 E1 F1200\nG1 E-1 F2400\n; stop printing object A id:0 copy 0\n"
      "; printing object B id:1 copy 0\nG1 X50 Y50 F6000\nG1 E1 F2400\nG1 X60 Y50 E1 F1200\n; stop printing object B id:1 copy 0\n"
      "; printing object A id:0 copy 0\nG1 X10 Y10 F6000\nG1 X0 Y10 E1 F1200\n; stop printing object A id:0 copy 0\n";
  const std::string out = without(plate, 1);
  CHECK_THAT(out, Catch::EndsWith("; printing object A id:0 copy 0\nG1 X10 Y10 F6000\nG1 E1 F2100\nG1 X0 Y10 E1 F1200\n"
                                  "; stop printing object A id:0 copy 0\n"));
}

TEST_CASE("object excluder: a stream that begins inside a layer leaves the object out there, and its lines go on in their own layer count",
          "[object_excluder]") {
  // gc-send --resume: the rest of layer 7, with no marker before it.
  const char* const rest =
      "G90\nM83\n"
      "; printing object A id:0 copy 0\nG1 X0 Y0 F6000\nG1 X10 Y0 E1 F1200\n; stop printing object A id:0 copy 0\n"
      "; printing object B id:1 copy 0\nG1 X50 Y50 F6000\nG1 X60 Y50 E1 F1200\n; stop printing object B id:1 copy 0\n";
  gcode::LayerMarkers markers;
  gcode::Pipeline p(markers);
  p.decide_layer_mode(gcode::LayerMode::Markers);  // as gc-send's resume decides it
  gcode::ObjectExcluder excluder(p.precision());
  excluder.start_inside_layer(7);
  excluder.exclude(1);
  int highest_layer_downstream = -1;
  gctest::FnStage downstream([&](const gcode::TrackedLine& t, gcode::Emitter& out) {
    highest_layer_downstream = std::max(highest_layer_downstream, t.layer);
    out.pass(t);
  });
  p.add(excluder);
  p.add(downstream);
  const std::string out = gctest::run_stages(p, rest);
  CHECK(out.find("G1 X60 Y50 E1") == std::string::npos);
  CHECK(out.find("G1 X10 Y0 E1 F1200") != std::string::npos);
  CHECK(excluder.dropped_extrusions() == 1);
  // The lines are the pipeline's start (layer 0): the one who resumed
  // places them in layer 7, once.
  CHECK(highest_layer_downstream == 0);
}

TEST_CASE("object excluder: without start_inside_layer, lines before the first layer are start code and stay",
          "[object_excluder]") {
  const char* const start =
      "G90\nM83\n; printing object B id:1 copy 0\nG1 X50 Y50 F6000\nG1 X60 Y50 E1 F1200\n; stop printing object B id:1 copy 0\n";
  CHECK(without(start, 1).find("G1 X60 Y50 E1 F1200") != std::string::npos);
}
