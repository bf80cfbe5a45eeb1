// transform/deform.hpp: the identity byte for byte on every fixture; the
// dish, arcs, relative and absolute E and G91 through the independent
// checker (tests/support/deform_check.hpp); refusals with their line; random
// smooth formulas never write a NaN, an infinity or an overlong line.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>

#include <fmt/format.h>

#include "deform_check.hpp"
#include "gcode/core/diagnostics.hpp"
#include "gcode/transform/deform.hpp"
#include "test_support.hpp"

using deformtest::P3;
using gcode::DeformFormulas;
using gcode::DeformFrame;
using gcode::DeformOptions;

namespace {

struct Deformed {
  std::string text;
  gcode::DeformStats stats;
  std::uint64_t warnings = 0;
};

Deformed deform(std::string_view input, const DeformFormulas& f, DeformOptions o = {}) {
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers);
  gcode::DeformMap map(f);
  gcode::Diagnostics diag("test", -1);
  gcode::Deformer stage(map, o, pipeline.precision(), &diag);
  pipeline.add(stage);
  Deformed d;
  d.text = gctest::run_stages(pipeline, input);
  d.stats = stage.stats();
  d.warnings = diag.warnings();
  return d;
}

// (Strings moved in: GCC 12 warns wrongly, -Wrestrict, on a short literal assigned to a member string.)
DeformFormulas xyz(std::string fx, std::string fy, std::string fz, std::string width = {}, std::string speed = {}) {
  DeformFormulas f;
  f.map = {std::move(fx), std::move(fy), std::move(fz)};
  f.width = std::move(width);
  f.speed = std::move(speed);
  return f;
}

// A small print in three layers: absolute E, a travel, an arc.
const char* kPart =
    "M82\nG28\nG1 Z5 F3000\nG1 X0 Y0 E0\n;LAYER:0\nG1 Z0.2 F600\nG1 X20 Y0 E1 F1200 ; edge\nG1 X20 Y20 E2\n"
    "G0 X10 Y10\n;LAYER:1\nG1 Z0.4\nG2 X30 Y10 I10 J0 E3.5\nG1 X30 Y30 E4.2\n;LAYER:2\nG1 Z0.6\nG1 X10 Y30 E5\n"
    "G1 E3 ; retract\nG1 X0 Y0 Z10\nG92 E0\nG1 E1\nM84\n";

void expect_exact(const std::string& in, const Deformed& d, const deformtest::Map& map, const deformtest::Factor& c,
                  double tol) {
  const deformtest::DeformCheck k = deformtest::check_deform(in, d.text, map, c, tol);
  INFO(d.text);
  CHECK(k.output_pieces > 0);
  CHECK(k.worst_out <= tol);
  CHECK(k.worst_back <= tol);
  CHECK(k.worst_e <= 0);
  CHECK(k.off_extrusion == 0);
  CHECK(k.entry_travels <= 1);
  CHECK(k.filament_out == Approx(k.filament_expected).epsilon(0.01));
}

}  // namespace

TEST_CASE("the identity reproduces every fixture byte for byte", "[deform]") {
  for (const std::string& name : gctest::fixture_names()) {
    INFO(name);
    const std::string in = gctest::read_file(gctest::fixture_path(name));
    const Deformed d = deform(in, xyz("x", "y", "z"));
    CHECK((d.text == in));
    CHECK(d.stats.moves == 0);
  }
}

TEST_CASE("Z = 0.3 z: layers 0.3 as thick, E 0.3 as much, arcs become chords, E after the layers shifted", "[deform]") {
  const Deformed d = deform(kPart, xyz("x", "y", "0.3*z"));
  auto map = [](const P3& p) { return P3{p[0], p[1], 0.3 * p[2]}; };
  expect_exact(kPart, d, map, [](const P3&) { return 0.3; }, 0.01);
  CHECK(d.stats.arcs == 1);
  CHECK(d.stats.section_min == Approx(0.3));
  CHECK(d.text.find("G1 F600 Z0.06\nG1 F1200 X20 E0.3 ; edge\n") != std::string::npos);
  CHECK(d.text.find("\nG2 ") == std::string::npos);
  // The start and end code as they were, the retraction from the shifted E, then G92 E0 puts E back in step.
  CHECK(d.text.rfind("M82\nG28\nG1 Z5 F3000\nG1 X0 Y0 E0\n", 0) == 0);
  // The arc's chords are shorter than the arc, and E follows the written length: 1.49996, not 0.3 x 5.
  CHECK(d.text.find("G1 X10 E1.49996\nG1 E-0.50004 ; retract\nG1 X0 Y0 Z10\nG92 E0\nG1 E1\nM84\n") !=
        std::string::npos);
}

TEST_CASE("relative E and G91: pieces sum exactly, the output's position followed", "[deform]") {
  const std::string in =
      "M83\nG28\n;LAYER:0\nG1 Z0.2 F600\nG1 X0 Y0\nG1 X40 Y0 E2 F1200\nG91\nG1 X0 Y40 E2\nG1 X-40 E2\nG90\nM83\n"
      ";LAYER:1\nG1 Z0.4\nG1 X0 Y0 E2\nG1 X40 Y0 E2\n;end\nG91\nG1 Z5\nG90\n";
  auto map = [](const P3& p) { return P3{p[0] + 0.002 * p[1] * p[1], p[1], p[2]}; };
  const Deformed d = deform(in, xyz("x + 0.002*y^2", "y", "z"));
  expect_exact(in, d, map, [](const P3&) { return 1.0; }, 0.01);
  CHECK(d.stats.pieces > d.stats.moves);  // the bent edges are cut
  const gcode::MachineState end = gctest::replay_state(d.text);
  CHECK(end.position[gcode::kX] == Approx(40));
  CHECK(end.position[gcode::kZ] == Approx(5.4));
}

TEST_CASE("the dish on a cylinder of arcs: every piece on the image, E = section x length", "[deform]") {
  std::string in = "M83\nG28\nG1 Z0.3 F600\nG1 X130 Y100 F3000\n";
  for (int layer = 0; layer < 6; ++layer)
    in += fmt::format(";LAYER:{}\nG1 Z{:.1f}\nG3 X130 Y100 I-20 J0 E3.3 F1800\n", layer, 0.3 * (layer + 1));
  DeformFormulas f;
  f.frame = DeformFrame::Cylindrical;
  f.map = {"r + 1.05*z", "theta", "0.3*z"};
  f.center_x = 110, f.center_y = 100;
  auto map = [](const P3& p) {
    const double r = std::hypot(p[0] - 110, p[1] - 100), a = std::atan2(p[1] - 100, p[0] - 110);
    return P3{110 + (r + 1.05 * p[2]) * std::cos(a), 100 + (r + 1.05 * p[2]) * std::sin(a), 0.3 * p[2]};
  };
  for (double tol : {0.01, 0.05}) {
    DeformOptions o;
    o.tolerance = tol;
    const Deformed d = deform(in, f, o);
    expect_exact(in, d, map, deformtest::layer_factor(map), tol);
  }
}

TEST_CASE("refused with the line: below the bed, down into the print, off the bed, a jump, no number", "[deform][errors]") {
  auto refused = [](const DeformFormulas& f, const std::string& what, std::uint64_t line, DeformOptions o = {}) {
    try {
      deform(kPart, f, o);
      FAIL("accepted");
    } catch (const gcode::DeformError& e) {
      CHECK_THAT(e.what(), Catch::Contains(what));
      CHECK_THAT(e.what(), Catch::StartsWith(fmt::format("line {}:", line)));
    }
  };
  refused(xyz("x", "y", "z - 0.3"), "below the bed", 6);
  refused(xyz("x - 20*z", "y", "z - 0.5*x + 20"), "down into what is printed", 12);
  DeformOptions bed;
  bed.has_bed = true;
  bed.bed = {0, 0, 25, 25};
  refused(xyz("x + 6", "y", "z"), "leaves the bed", 7, bed);  // the edge to X20 goes to X26
  refused(xyz("x + (x > 15 ? 3 : 0)", "y", "z"), "jumps", 7);
  refused(xyz("x + sqrt(y - 5)", "y", "z"), "no number", 6);
  refused(xyz("x", "y", "0.2 + 0*z"), "squashed to nothing", 7);
  DeformOptions force;
  force.force = true;
  CHECK_NOTHROW(deform(kPart, xyz("x + (x > 15 ? 3 : 0)", "y", "z"), force));
}

TEST_CASE("the width and speed factors, the caps, and warnings where the section leaves 0.3-3", "[deform]") {
  DeformOptions o;
  o.max_speed = 30;
  const Deformed d = deform(kPart, xyz("x", "y", "z", "1 + x/20", "2"), o);
  auto map = [](const P3& p) { return p; };
  expect_exact(kPart, d, map, [](const P3& p) { return 1 + p[0] / 20; }, 0.01);
  CHECK(d.stats.section_max == Approx(2.5).margin(0.05));
  CHECK(d.stats.speed_max == Approx(30));
  CHECK(d.stats.capped > 0);
  CHECK(deform(kPart, xyz("x", "y", "z", "4")).warnings >= 1);
}

TEST_CASE("random smooth formulas: never a NaN, an infinity or a line over Marlin's 96 bytes", "[deform]") {
  const std::string in = gctest::head_of("cura_vase_0.2_spiralize.gcode", 4000);
  std::mt19937 rng(24);
  std::uniform_real_distribution<double> amp(0, 2), freq(0.01, 0.3), phase(0, 6.28);
  for (int round = 0; round < 6; ++round) {
    const double a = amp(rng), b = freq(rng), c = phase(rng), g = amp(rng) / 20, h = freq(rng);
    const std::string fx = fmt::format("x + {}*sin({}*y + {})", a, b, c);
    const std::string fz = fmt::format("z*(1 + {}*cos({}*x))", g, h);
    INFO(fx << " | " << fz);
    const Deformed d = deform(in, xyz(fx, "y", fz));
    for (const std::string& line : gctest::split_lines(d.text)) {
      CHECK(line.size() <= 96);
      CHECK(line.find("nan") == std::string::npos);
      CHECK(line.find("inf") == std::string::npos);
    }
    auto map = [=](const P3& p) { return P3{p[0] + a * std::sin(b * p[1] + c), p[1], p[2] * (1 + g * std::cos(h * p[0]))}; };
    const deformtest::DeformCheck k = deformtest::check_deform(in, d.text, map, deformtest::layer_factor(map), 0.01);
    CHECK(k.worst_out <= 0.01);
    CHECK(k.worst_e <= 0);
  }
}
