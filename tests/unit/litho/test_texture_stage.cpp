// The texture stage behind gc-subdivide's stage: the same path, each piece at
// its pixel's speed with E per second unchanged, F only where the speed
// changes, absolute E brought back in step before anything else uses E.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "gcode/core/line.hpp"
#include "gcode/litho/texture_stage.hpp"
#include "gcode/transform/subdivide.hpp"
#include "test_support.hpp"

using gcode::litho::GreyImage;

namespace {

// Black on the left half, white on the right: 0..10 mm and 10..20 mm along X.
GreyImage halves() { return GreyImage(2, 2, {0, 255, 0, 255}); }

std::string program(bool relative) {
  const std::string e1 = "E1", e2 = relative ? "E1" : "E2";
  return std::string(relative ? "M83\n" : "M82\n") +
         "G92 E0\n"
         "G1 Z0.2 F600\n"
         "G1 X0 Y0 F3000\n"
         "G1 X20 Y0 " + e1 + " F1800 ; wall\n"
         "G1 X20 Y2 " + e2 + "\n" +
         (relative ? "G1 E-1 F2400\n" : "G1 E1 F2400\n") +  // a retraction
         "G0 X0 Y2 F6000\n"
         + (relative ? "G1 E1\n" : "G1 E2\n") +
         + (relative ? "G1 X0 Y4 E1\n" : "G1 X0 Y4 E3\n");
}

struct Painted {
  std::string text;
  gcode::litho::TextureStats stats;
};

Painted paint(const std::string& input, double resolution = 0.5) {
  gcode::litho::TextureMapping m;
  m.projection = gcode::litho::Projection::Y;
  m.center_x = 10;
  m.width = 20;
  m.height = 20;
  const GreyImage image = halves();
  const gcode::litho::TextureProjection projection(m, image.width(), image.height());
  gcode::litho::SpeedMapping speeds;
  speeds.low = 10;
  speeds.high = 40;
  const gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers);
  gcode::SubdivideOptions split{.max_length = resolution, .split_travel = false};
  gcode::Subdivider subdivider(split, pipeline.precision(), nullptr);
  gcode::litho::TextureStage stage(projection, image, speeds, 0, pipeline.precision(), nullptr, {"header"});
  pipeline.add(subdivider);
  pipeline.add(stage);
  Painted p;
  p.text = gctest::run_stages(pipeline, input);
  p.stats = stage.stats();
  return p;
}

}  // namespace

TEST_CASE("texture stage: the path is gc-subdivide's, speeds follow the pixels, E per second is kept",
          "[litho][texture-stage]") {
  for (bool relative : {true, false}) {
    INFO((relative ? "M83" : "M82"));
    const std::string input = program(relative);
    const Painted p = paint(input);
    const std::string cut = gctest::subdivide(input, {.max_length = 0.5, .split_travel = false}).text;
    const auto a = gctest::replay_moves(cut), b = gctest::replay_moves(p.text);
    // Same moves in the same order (the G92 lines added are not moves with length).
    std::vector<const gctest::ReplayedMove*> ma, mb;
    for (const auto& m : a) if (m.move.length > 0) ma.push_back(&m);
    for (const auto& m : b) if (m.move.length > 0) mb.push_back(&m);
    REQUIRE(ma.size() == mb.size());
    REQUIRE(ma.size() > 40);
    int black = 0, white = 0;
    for (std::size_t i = 0; i < ma.size(); ++i) {
      const gcode::Move &o = ma[i]->move, &n = mb[i]->move;
      for (int axis = 0; axis < 3; ++axis) REQUIRE(o.end[axis] == n.end[axis]);
      if (!o.extruding) {
        REQUIRE(n.feedrate == o.feedrate);
        continue;
      }
      const double before = o.filament / (o.length / o.feedrate), after = n.filament / (n.length / n.feedrate);
      REQUIRE(after == Approx(before).epsilon(0.005));
      const bool on_wall = o.end[gcode::kY] == 0;
      if (!on_wall) continue;
      const double mid_x = (o.start[gcode::kX] + o.end[gcode::kX]) / 2;
      REQUIRE(n.feedrate == (mid_x < 10 ? 600 : 2400));
      (mid_x < 10 ? black : white)++;
    }
    CHECK(black > 10);
    CHECK(white > 10);
    // F only where the speed changes: once into black, once into white on the
    // wall, then the moves along Y at x = 20 (white) and x = 0 (black).
    CHECK(p.stats.speed_words <= 4);
    // The retraction and the travel are the input's lines.
    CHECK_THAT(p.text, Catch::Contains(relative ? "\nG1 E-1 F2400\nG0 X0 Y2 F6000\n" : "G1 E1 F2400\nG0 X0 Y2 F6000\n"));
    CHECK_THAT(p.text, Catch::StartsWith(relative ? "; header\nM83\n" : "; header\nM82\n"));
    if (!relative) {
      CHECK(p.stats.resyncs == 1);  // before the retraction; the unretraction then ends where the input's does
      CHECK_THAT(p.text, Catch::Contains("G92 E2 ; gc-litho: E back in step\nG1 E1 F2400\n"));
    } else {
      CHECK(p.stats.resyncs == 0);
    }
  }
}

TEST_CASE("texture stage: a move off the picture keeps its speed and gets the input's F back after a run",
          "[litho][texture-stage]") {
  // The wall from x = 20 to 30 lies right of the picture (0..20).
  const std::string input = "M83\nG1 Z0.2 F600\nG1 X5 Y0 F3000\nG1 X30 Y0 E2 F1800\nG1 X30 Y5 E1\n";
  const Painted p = paint(input);
  CHECK(p.stats.outside > 0);
  CHECK(p.stats.restores == 1);
  const auto moves = gctest::replay_moves(p.text);
  for (const auto& m : moves)
    if (m.move.extruding && m.move.start[gcode::kX] >= 20) REQUIRE(m.move.feedrate == 1800);
}

TEST_CASE("texture stage: the input's own G92 E puts absolute E back in step without a line of ours",
          "[litho][texture-stage]") {
  const std::string input = "M82\nG92 E0\nG1 Z0.2 F600\nG1 X0 Y0 F3000\nG1 X20 Y0 E1 F1800\nG92 E0\nG1 X20 Y2 E0.1\n";
  const Painted p = paint(input);
  CHECK(p.stats.resyncs == 0);
  CHECK(p.stats.textured > 10);
  // After the input's G92 E0 the next piece starts from 0 again, scaled.
  const auto moves = gctest::replay_moves(p.text);
  double after_reset = 0;
  for (const auto& m : moves)
    if (m.move.extruding && m.move.start[gcode::kX] == 20) after_reset += m.move.filament;
  CHECK(after_reset == Approx(0.1 * 1800 / 2400).margin(1e-5));  // x = 20: white, 40 mm/s
}
