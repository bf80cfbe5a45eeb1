// gc-deform: the identity byte for byte on every fixture (file and pipe);
// gc-shape's cup into the dish, onto the sphere and into the heart, and
// Cura's and Slic3r's vases bent, all through the independent checker
// (tests/support/deform_check.hpp: every output point within the tolerance
// of the formula's image of the input path, nothing left out, E = the
// section law on every piece, the filament against the deformed bead
// volume); gc-layers and the virtual printer read the result; refusals and
// usage errors with their line or position; -i left alone on a refusal;
// examples/procedural's Makefile end to end.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>

#include <nlohmann/json.hpp>

#include "deform_check.hpp"
#include "test_support.hpp"

using deformtest::P3;
using gctest::quote;
using gctest::run;
using gctest::tool_command;

namespace {

// (x, y, z) -> (FR, FTHETA, FZ) about (cx, cy), as --cylinder defines it.
deformtest::Map cylinder(double cx, double cy, std::function<P3(double r, double theta, double z)> f) {
  return [=](const P3& p) {
    const P3 q = f(std::hypot(p[0] - cx, p[1] - cy), std::atan2(p[1] - cy, p[0] - cx), p[2]);
    return P3{cx + q[0] * std::cos(q[1]), cy + q[0] * std::sin(q[1]), q[2]};
  };
}

std::string shape(const std::string& args) {
  auto r = run(tool_command("gc-shape", args));
  REQUIRE(r.status == 0);
  return r.out;
}

// gc-deform on `input`, then the checker with the same formula written in C++.
void deformed_exactly(const std::string& input, const std::string& args, const deformtest::Map& map,
                      const deformtest::Factor& section, double tol = 0.01) {
  auto r = run(tool_command("gc-deform", args + " -v -"), input);
  INFO(args << "\n" << r.err);
  REQUIRE(r.status == 0);
  const deformtest::DeformCheck c = deformtest::check_deform(input, r.out, map, section, tol);
  CHECK(c.output_pieces > 0);
  INFO("worst at output line " << c.worst_out_line + 1);
  CHECK(c.worst_out <= tol);
  CHECK(c.worst_back <= tol);
  CHECK(c.worst_e <= 0);
  CHECK(c.off_extrusion == 0);
  CHECK(c.entry_travels <= 1);
  CHECK(c.filament_out == Approx(c.filament_expected).epsilon(0.01));
  auto layers = run(tool_command("gc-layers", "--json -"), r.out);
  REQUIRE(layers.status == 0);
  auto before = run(tool_command("gc-layers", "--json -"), input);
  CHECK(nlohmann::json::parse(layers.out)["summary"]["layers"] == nlohmann::json::parse(before.out)["summary"]["layers"]);
}

}  // namespace

TEST_CASE("gc-deform --xyz x y z reproduces every fixture byte for byte, from a file and a pipe", "[gc-deform]") {
  for (const std::string& name : gctest::fixture_names()) {
    INFO(name);
    const std::string path = gctest::fixture_path(name);
    auto r = run(tool_command("gc-deform", "-q --xyz x y z " + quote(path)));
    CHECK(r.status == 0);
    CHECK((r.out == gctest::read_file(path)));
  }
  const std::string vase = gctest::read_file(gctest::fixture_path("cura_vase_0.2_spiralize.gcode"));
  auto r = run(tool_command("gc-deform", "-q --cylinder r theta z"), vase);  // the part's centre from Cura's header
  CHECK(r.status == 0);
  CHECK((r.out == vase));
}

TEST_CASE("gc-deform: the cup into the dish, onto the sphere, into the heart, exact to the tolerance", "[gc-deform]") {
  const std::string cup = shape("helix --diameter 60 --height 12");
  auto dish = cylinder(110, 110, [](double r, double t, double z) { return P3{r + 1.05 * z, t, 0.3 * z}; });
  deformed_exactly(cup, "--cylinder 'r + 1.05*z' theta '0.3*z'", dish, deformtest::layer_factor(dish));
  deformed_exactly(cup, "--tolerance 0.05 --cylinder 'r + 1.05*z' theta '0.3*z'", dish, deformtest::layer_factor(dish),
                   0.05);
  const double h = 94.25;
  auto sphere = cylinder(110, 110, [h](double r, double t, double z) {
    return P3{30 * std::sin(std::numbers::pi * z / h), t, r - 30 * std::cos(std::numbers::pi * z / h)};
  });
  deformed_exactly(shape("helix --diameter 60 --height 20"),
                   "--keep-section --cylinder '30*sin(pi*z/94.25)' theta 'r - 30*cos(pi*z/94.25)'", sphere,
                   [](const P3&) { return 1.0; });
  auto heart = [](const P3& p) { return P3{p[0] + 0.5 * p[2] * std::sqrt(std::fabs(p[1] - 110) / 20), p[1], p[2]}; };
  deformed_exactly(shape("helix --diameter 40 --height 6"), "--xyz 'x + 0.5*z*sqrt(abs(y - 110)/20)' y z", heart,
                   [](const P3&) { return 1.0; });
}

TEST_CASE("gc-deform on real vases (Cura spiralize, Slic3r verbose and unmarked): exact, and printable", "[gc-deform]") {
  // r times a factor: continuous at the axis, which the bottoms' infill crosses (r + 0.8 sin(...) would jump there).
  const std::string wave = "--cylinder 'r*(1 + 0.03*sin(5*theta + z/4))' theta 'z*1.2'";
  for (const char* name : {"cura_vase_0.2_spiralize.gcode", "slic3r_vase_0.2_spiral_verbose.gcode",
                           "slic3r_vase_0.2_spiral_unmarked.gcode"}) {
    INFO(name);
    const std::string text = gctest::read_file(gctest::fixture_path(name));
    // The centre as the tool finds it: the print's box (Cura) or its extrusions (Slic3r).
    const gctest::LinePlace places = gctest::places_of(text);
    double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
    for (const gctest::ReplayedMove& m : gctest::replay_moves(text))
      if (places.layer[m.line_index] > 0 && m.move.extruding)
        for (int a = 0; a < 2; ++a)
          lo[a] = std::min({lo[a], m.move.start[a], m.move.end[a]}), hi[a] = std::max({hi[a], m.move.start[a], m.move.end[a]});
    const double cx = (lo[0] + hi[0]) / 2, cy = (lo[1] + hi[1]) / 2;
    auto map = cylinder(cx, cy, [](double r, double t, double z) { return P3{r * (1 + 0.03 * std::sin(5 * t + z / 4)), t, 1.2 * z}; });
    const std::string center = std::string(" --center ") + std::to_string(cx) + "," + std::to_string(cy);
    deformed_exactly(text, wave + center, map, deformtest::layer_factor(map));
  }
}

TEST_CASE("gc-deform output prints on the virtual printer", "[gc-deform][serial]") {
  auto r = run(tool_command("gc-shape", "cylinder --diameter 30 --height 3") + " | " +
               tool_command("gc-deform", "--cylinder 'r + 0.5*z' theta '0.5*z' --bed 220x220") + " | " +
               tool_command("gc-send", "--port virtual:time-scale=5000,heat-rate=1000"));
  INFO(r.err);
  CHECK(r.status == 0);
}

TEST_CASE("gc-deform refuses what cannot print, with the line, -i leaves the file alone", "[gc-deform][errors]") {
  const std::string dir = gctest::temp_dir(), file = dir + "/cup.gcode";
  const std::string cup = shape("helix --diameter 60 --height 3");
  gctest::write_file(file, cup);
  struct Refusal {
    const char* args;
    const char* says;
  } refusals[] = {
      {"--xyz x y 'z - 1'", "below the bed"},
      {"--xyz x y '3 - z'", "upside down"},
      {"--xyz 'x - 3*z' y 'z - 2*x + 300'", "down into what is printed"},
      {"--xyz 'x + 100' y z --bed 220x220", "leaves the bed"},
      {"--xyz 'x + (y > 110 ? 2 : 0)' y z", "jumps"},
      {"--xyz x y 'z + sqrt(x - 130)'", "no number"},
  };
  for (const Refusal& f : refusals) {
    INFO(f.args);
    auto r = run(tool_command("gc-deform", std::string(f.args) + " -i " + quote(file)));
    CHECK(r.status == 1);
    CHECK(r.err.rfind("gc-deform: line ", 0) == 0);
    CHECK(r.err.find(f.says) != std::string::npos);
    CHECK((gctest::read_file(file) == cup));
  }
  auto forced = run(tool_command("gc-deform", "--force --xyz 'x + (y > 110 ? 2 : 0)' y z -"), cup);
  CHECK(forced.status == 0);
}

TEST_CASE("gc-deform: moves in inches (G20) in the layers pass under the identity, are refused when bent, pass with --force",
          "[gc-deform][errors]") {
  const std::string inches =
      "G21\nG90\nM82\n;LAYER:0\nG1 Z0.2 F600\nG1 X10 Y10 E0.5 F1200\nG20\nG1 X1 Y1 E0.6\nG21\nG1 X30 Y30 E1\n";
  auto same = run(tool_command("gc-deform", "--xyz x y z -"), inches);
  CHECK(same.status == 0);
  CHECK((same.out == inches));
  auto bent = run(tool_command("gc-deform", "--xyz 'x + 1' y z -"), inches);
  CHECK(bent.status == 1);
  CHECK(bent.err.find("line 8: the layers move in inches (G20)") != std::string::npos);
  auto forced = run(tool_command("gc-deform", "--force --xyz 'x + 1' y z -"), inches);
  INFO(forced.err);
  CHECK(forced.status == 0);
  CHECK(forced.out.find("\nG20\nG1 X1 Y1 E0.6\n") != std::string::npos);  // as it was
  CHECK(forced.out.find("X11") != std::string::npos);                      // the mm moves are bent
}

TEST_CASE("gc-deform: bad formulas and options are usage errors naming the formula and the position", "[gc-deform][errors]") {
  struct Bad {
    const char* args;
    const char* says;
  } bad[] = {
      {"--xyz x y", "--xyz"},
      {"--xyz x y 'z +* 2'", "--xyz FZ 'z +* 2'"},
      {"--cylinder r 'theta + x' z", "--cylinder FTHETA 'theta + x': Unexpected token \"x\" found at character 9"},
      {"--xyz x y z --width 'foo'", "--width FC 'foo'"},
      {"--xyz x y z --tolerance 0.001", "--tolerance"},
      {"--xyz x y z --cylinder r theta z", "excludes"},
      {"", "give the deformation"},
      {"--xyz x y z --bed 20", "--bed"},
  };
  for (const Bad& b : bad) {
    INFO(b.args);
    auto r = run(tool_command("gc-deform", b.args), "G1 X1\n");
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.find(b.says) != std::string::npos);
  }
  auto pipe = run("printf 'G1 X1 Y1 E1\\n' | " + tool_command("gc-deform", "--cylinder r theta z"));
  CHECK(pipe.status == 2);
  CHECK(pipe.err.find("--center") != std::string::npos);
}

TEST_CASE("examples/procedural: every example made, drawn by gc-layers --svg and printed on the virtual printer",
          "[gc-deform][examples]") {
  const std::string dir = gctest::temp_dir();
  const std::string examples = std::string(GC_FIXTURES_DIR) + "/../../examples/procedural";
  auto r = run("make -s -C " + quote(examples) + " OUT=" + quote(dir) + " BIN=" + quote(std::string(GC_TOOLS_DIR)) +
               " SCALE=small print");
  INFO(r.err);
  REQUIRE(r.status == 0);
  for (const char* name : {"dish", "sphere", "heart", "globe", "vase"}) {
    INFO(name);
    CHECK(std::filesystem::file_size(dir + "/" + name + ".gcode") > 1000);
    CHECK(gctest::read_file(dir + "/" + name + ".svg").find("<svg") != std::string::npos);
  }
}
