// procedural/bottom_fill.hpp: concentric loops a line width apart, layers
// alternating so that the last ends on its outermost loop.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "gcode/procedural/bottom_fill.hpp"
#include "gcode/procedural/mesh_slicer.hpp"
#include "gcode/procedural/stl_reader.hpp"
#include "mesh/loop_distance.hpp"
#include "mesh/mesh_maker.hpp"

namespace test_bottom_fill {

using gcode::procedural::BottomFillOptions;
using gcode::procedural::HeightProblems;
using gcode::procedural::MeshSlicer;
using gcode::procedural::ShapeLayer;

TEST_CASE("bottom_fill: a square's loops one line width apart, outermost first", "[shape][mesh]") {
  const gcode::Polygon square = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const auto loops = gcode::procedural::fill_loops(square, 0.5, 0.01);
  CHECK(loops.size() == 10);  // 0, 0.5, .. 4.5 mm in: the last 1 mm wide
  for (std::size_t i = 0; i < loops.size(); ++i) {
    double left = 1e9;
    for (const gcode::Point2& p : loops[i]) left = std::min(left, p.x);
    CHECK(left == Approx(0.5 * static_cast<double>(i)).margin(1e-4));
  }
}

TEST_CASE("bottom_fill: a wavy loop's loops k line widths from it, as few points as it has", "[shape][mesh]") {
  // Bumps sharper than the line width fold the offsets (Clipper's case); each loop is the outline
  // moved in by k line widths, so its corners lie k widths from the outline, and the loops do not
  // gather points as they shrink.
  gcode::Polygon wavy;
  for (int i = 0; i < 290; ++i) {
    const double a = 2 * M_PI * i / 290, r = 10 + 1.5 * std::sin(8 * a);
    wavy.push_back({r * std::cos(a), r * std::sin(a)});
  }
  const auto loops = gcode::procedural::fill_loops(wavy, 0.5, 0.01);
  REQUIRE(loops.size() >= 17);
  std::size_t most = 0;
  for (std::size_t k = 1; k < loops.size(); ++k) {
    most = std::max(most, loops[k].size());
    INFO("loop " << k);
    for (const gcode::Point2& p : loops[k])
      CHECK(meshtest::loop_distance(p, wavy) == Approx(0.5 * static_cast<double>(k)).margin(0.01 / 4));
  }
  CHECK(most <= 2 * wavy.size());
}

TEST_CASE("bottom_fill: layers at their heights, the last ending outside", "[shape][mesh]") {
  const auto mesh = gcode::procedural::read_stl(meshtest::binary_stl(meshtest::cylinder(10, 5, 90)), "m.stl");
  MeshSlicer slicer(mesh);
  std::vector<ShapeLayer> layers;
  HeightProblems problems;
  gcode::procedural::bottom_fill(slicer, BottomFillOptions{3, 0.3, 0.5, 0.01, 5}, layers, problems);
  CHECK(problems.empty());
  REQUIRE(layers.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK(layers[i].bottom);
    CHECK(layers[i].points.front().travel == (i > 0));  // the first layer's first point is the path's start
    CHECK(layers[i].points.front().z == Approx(0.3 * static_cast<double>(i + 1)));
  }
  const auto& end = layers.back().points.back();
  CHECK(std::hypot(end.x, end.y) == Approx(10 * std::cos(M_PI / 90) - 0.25).margin(0.01));
}

}  // namespace test_bottom_fill
