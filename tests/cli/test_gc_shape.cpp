// gc-shape: every primitive through gc-layers (one layer a turn), the
// independent replay checker (tests/support/shape_check.hpp: on the curve, E
// = the bead, nothing but extrusion in the layers), gc-layers' time and SVG,
// and the virtual printer; options, errors and --help against the man page.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "shape_check.hpp"
#include "test_support.hpp"

using gctest::quote;
using gctest::run;
using gctest::tool_command;
using gcode::procedural::ShapeKind;
using gcode::procedural::ShapeOptions;

namespace {

struct Case {
  const char* args;
  ShapeKind kind;
  int layers;  // turns (+ a cylinder's bottom; flat shapes: 1)
  double pitch;
};

}  // namespace

TEST_CASE("gc-shape: every primitive, one layer a turn, on its curve, E = the bead, printable", "[gc-shape]") {
  const Case cases[] = {
      {"circle --diameter 30", ShapeKind::Circle, 1, 0},
      {"spiral --diameter 30 --inner-diameter 4", ShapeKind::Spiral, 1, 0},
      {"helix --diameter 30 --height 8", ShapeKind::Helix, 27, 8.0 / 27},
      {"cylinder --diameter 30 --height 6 --layer-height 0.2", ShapeKind::Cylinder, 1 + 29, 5.8 / 29},
      {"polygon --diameter 30 --height 6 --sides 5", ShapeKind::Polygon, 20, 0.3},
      {"cone --diameter 30 --top-diameter 12 --height 6 --tolerance 0.005", ShapeKind::Cone, 20, 0.3},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    auto r = run(tool_command("gc-shape", c.args));
    REQUIRE(r.status == 0);
    CHECK(r.err.empty());
    ShapeOptions o;
    o.kind = c.kind;
    o.diameter = 30;
    o.inner_diameter = c.kind == ShapeKind::Spiral ? 4 : 0;
    o.top_diameter = 12;
    o.sides = 5;
    o.layer_height = c.kind == ShapeKind::Cylinder ? 0.2 : 0.3;
    o.tolerance = c.kind == ShapeKind::Cone ? 0.005 : 0.01;
    const int turns = c.kind == ShapeKind::Cylinder ? c.layers - 1 : (c.pitch > 0 ? c.layers : 0);
    const shapetest::ShapeCheck check = shapetest::check_shape(r.out, o, c.pitch, turns);
    CHECK(check.pieces > 0);
    CHECK(check.worst_chord <= o.tolerance);
    CHECK(check.worst_e <= 0);
    CHECK(check.other_moves == 0);  // the helix: no layer-change move, no retraction

    auto layers = run(tool_command("gc-layers", "--json --time -"), r.out);
    REQUIRE(layers.status == 0);
    const nlohmann::json j = nlohmann::json::parse(layers.out);
    CHECK(j["summary"]["layers"] == c.layers);
    CHECK(j["summary"]["filament_mm"].get<double>() == Approx(check.filament).margin(1e-4));
    auto svg = run(tool_command("gc-layers", "--svg 1 --svg-out - -"), r.out);
    CHECK(svg.status == 0);
    CHECK(svg.out.find("<svg") != std::string::npos);
  }
}

TEST_CASE("gc-shape prints on the virtual printer", "[gc-shape][serial]") {
  auto r = run(tool_command("gc-shape", "cylinder --diameter 20 --height 2 --retract 0.8") + " | " +
               tool_command("gc-send", "--port virtual:time-scale=5000,heat-rate=1000"));
  INFO(r.err);
  CHECK(r.status == 0);
}

TEST_CASE("gc-shape: the header, -o, --start/--end files", "[gc-shape]") {
  const std::string dir = gctest::temp_dir();
  gctest::write_file(dir + "/start.gcode", "G28\nM109 S215");
  gctest::write_file(dir + "/end.gcode", "M84\n");
  auto r = run(tool_command("gc-shape", "helix --height 1 --start " + quote(dir + "/start.gcode") + " --end " +
                                            quote(dir + "/end.gcode") + " -o " + quote(dir + "/out.gcode") + " -v"));
  REQUIRE(r.status == 0);
  CHECK(r.out.empty());
  CHECK(r.err.find("gc-shape: helix: 4 layers") != std::string::npos);
  const std::string text = gctest::read_file(dir + "/out.gcode");
  for (const char* s : {";  shape = helix\n", ";  pitch = 0.25 mm, 4 turns\n", "G28\nM109 S215\nG90\nM83",
                        ";MAXZ:1\n", ";LAYER:3\n"})
    CHECK(text.find(s) != std::string::npos);
  CHECK(text.substr(text.size() - 4) == "M84\n");
  CHECK(text.find("M190") == std::string::npos);
}

TEST_CASE("gc-shape: usage errors exit 2 and name the option, a missing --start file exits 1", "[gc-shape][errors]") {
  for (const char* args : {"", "sphere", "helix --height 0.1", "polygon --sides 2", "helix --tolerance 0.001",
                           "helix --center 1", "helix --diameter -1", "spiral --diameter 10 --inner-diameter 12",
                           "helix --nozzle-temp 500"}) {
    INFO(args);
    auto r = run(tool_command("gc-shape", args));
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("gc-shape: ", 0) == 0);
  }
  auto r = run(tool_command("gc-shape", "helix --start /no/such/file"));
  CHECK(r.status == 1);
  CHECK(r.err.find("--start /no/such/file") != std::string::npos);
}
