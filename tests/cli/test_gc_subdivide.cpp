// gc-subdivide on real slicer output, checked by the independent replay
// checker (tests/support/subdivide_check.hpp): pieces on their moves, filament
// and state preserved, limits kept, other lines byte for byte; idempotence,
// selections, errors, and --help against the man page.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

#include "gcode/core/layer_marker.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line_reader.hpp"
#include "subdivide_check.hpp"
#include "test_support.hpp"

using gctest::fixture_path;
using gctest::quote;
using gctest::read_file;
using gctest::run;

namespace {


// Runs the tool on `input` (stdin), checks the invariants and that a second
// run changes nothing. Returns the checker's report.
gctest::SubdivideCheck run_checked(const std::string& input, const std::string& args,
                                   const gctest::SubdivideLimits& limits) {
  auto r = run(gctest::tool_command("gc-subdivide", args), input);
  REQUIRE(r.status == 0);
  CHECK(r.err == "");
  gctest::SubdivideCheck c = gctest::check_subdivision(input, r.out, limits);
  CHECK(c.first_failure() == "");
  auto again = run(gctest::tool_command("gc-subdivide", args), r.out);
  REQUIRE(again.status == 0);
  CHECK((again.out == r.out));  // idempotent
  return c;
}

gctest::SubdivideLimits max_limits(double mm) {
  gctest::SubdivideLimits l;
  l.max = mm;
  l.min = std::min(0.05, mm / 2);
  return l;
}

// The first `lines` lines of a fixture (a cut of its first layers).
std::string head_of(const std::string& name, std::size_t lines) {
  std::string text = read_file(fixture_path(name));
  std::size_t pos = 0;
  for (std::size_t i = 0; i < lines && pos != std::string::npos; ++i) pos = text.find('\n', pos + 1);
  return pos == std::string::npos ? text : text.substr(0, pos + 1);
}

// Per input line, its layer (0 outside layers) and ;TYPE: feature, as the
// tracker (gc-layers' numbering) sees them.
struct LinePlace {
  std::vector<int> layer;
  std::vector<std::string> feature;
  std::vector<double> layer_z;
};
LinePlace places_of(const std::string& text) {
  struct Sink : gcode::LayerSink {
    LinePlace p;
    gcode::LayerTracker* tracker = nullptr;
    double z = 0;
    void on_layer(const gcode::LayerInfo& l, const gcode::MachineState&) override { z = l.z; }
    void on_line(const gcode::TrackedLine& t) override {
      p.layer.push_back(t.region == gcode::Region::Layer ? t.layer : 0);
      p.feature.push_back(t.feature >= 0 ? tracker->feature_name(t.feature) : std::string());
      p.layer_z.push_back(z);
    }
  } sink;
  gcode::LayerMarkers markers;
  gcode::LayerTracker tracker(sink, markers);
  sink.tracker = &tracker;
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) tracker.push(raw);
  tracker.finish();
  return sink.p;
}

}  // namespace

TEST_CASE("every fixture at max 2 mm and at latency 0.25 s: the checker holds and a second run changes nothing",
          "[gc-subdivide][fixtures]") {
  for (const std::string& name : gctest::fixture_names()) {
    INFO(name);
    std::string text = read_file(fixture_path(name));
    gctest::SubdivideCheck c = run_checked(text, "--max 2", max_limits(2));
    CHECK(c.moves_split > 100);
    gctest::SubdivideLimits latency;
    latency.latency = 0.25;
    gctest::SubdivideCheck d = run_checked(text, "--latency 0.25", latency);
    CHECK(d.moves_split > 0);
  }
}

TEST_CASE("smaller fixtures at 0.5 mm and first layers at 0.1 mm", "[gc-subdivide][fixtures]") {
  for (const char* name : {"slic3r_cube_0.2_abs_reprap_skirt.gcode", "cura_cube_0.2_abs_zhop_skirt.gcode"}) {
    INFO(name);
    CHECK(run_checked(read_file(fixture_path(name)), "--max 0.5", max_limits(0.5)).pieces > 10000);
  }
  for (const char* name : {"cura_pegs_0.2_rel_fwretract.gcode", "prusa_dome_varlayer_ender3_abs.gcode",
                           "slic3r_cylinder_0.3_rel_zhop_brim.gcode"}) {
    INFO(name);
    CHECK(run_checked(head_of(name, 2500), "--max 0.1", max_limits(0.1)).pieces > 10000);
  }
}

TEST_CASE("a file with CRLF endings keeps them on every piece", "[gc-subdivide]") {
  std::string text = head_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 1500);
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  text = crlf;
  auto r = run(gctest::tool_command("gc-subdivide", "--max 0.5"), text);
  REQUIRE(r.status == 0);
  CHECK(gctest::check_subdivision(text, r.out, max_limits(0.5)).first_failure() == "");
  for (const std::string& l : gctest::split_lines(r.out)) REQUIRE(l.substr(l.size() - 2) == "\r\n");
}

TEST_CASE("selections by layer and height and feature split only there", "[gc-subdivide][select]") {
  std::string name = "prusa_cube_0.2_mk3s_rel_zhop.gcode";
  std::string text = read_file(fixture_path(name));
  LinePlace place = places_of(text);
  REQUIRE(place.layer.size() == gctest::split_lines(text).size());

  SECTION("layers 3-5") {
    gctest::SubdivideLimits l = max_limits(0.5);
    for (int layer : place.layer) l.selected.push_back(layer >= 3 && layer <= 5);
    CHECK(run_checked(text, "--max 0.5 --layers 3-5", l).moves_split > 100);
  }
  SECTION("the last two layers") {
    gctest::SubdivideLimits l = max_limits(0.5);
    int last = *std::max_element(place.layer.begin(), place.layer.end());
    for (int layer : place.layer) l.selected.push_back(layer >= last - 1);
    CHECK(run_checked(text, "--max 0.5 --layers -2", l).moves_split > 10);
  }
  SECTION("heights 1 to 1.4 mm") {
    gctest::SubdivideLimits l = max_limits(0.5);
    for (std::size_t i = 0; i < place.layer.size(); ++i)
      l.selected.push_back(place.layer[i] > 0 && place.layer_z[i] >= 1 - 1e-6 && place.layer_z[i] <= 1.4 + 1e-6);
    CHECK(run_checked(text, "--max 0.5 --z-range 1:1.4", l).moves_split > 100);
  }
  SECTION("external perimeters only") {
    gctest::SubdivideLimits l = max_limits(0.5);
    for (const std::string& f : place.feature) l.selected.push_back(f == "External perimeter");
    CHECK(run_checked(text, "--max 0.5 --types 'external perimeter'", l).moves_split > 100);
  }
}

TEST_CASE("no-travel keeps travel whole and arcs keep keeps arcs", "[gc-subdivide]") {
  std::string text = head_of("cura_cube_0.2_abs_zhop_skirt.gcode", 3000);
  gctest::SubdivideLimits l = max_limits(0.5);
  l.travel = false;
  run_checked(text, "--max 0.5 --no-travel", l);
  std::string arcs = "G90\nM83\nG1 X10 Y0 F1800\nG2 I-10 J0 E3\nG3 X0 Y10 R10 E1\n";
  auto keep = run(gctest::tool_command("gc-subdivide", "--max 0.5 --arcs keep"), arcs);
  CHECK(keep.out.find("G2 I-10 J0 E3\nG3 X0 Y10 R10 E1\n") != std::string::npos);
  gctest::SubdivideLimits a = max_limits(0.5);
  CHECK(run_checked(arcs, "--max 0.5", a).arcs == 2);
  auto only_arcs = run(gctest::tool_command("gc-subdivide", "--arcs split"), arcs);
  REQUIRE(only_arcs.status == 0);
  CHECK(only_arcs.out.rfind("G90\nM83\nG1 X10 Y0 F1800\nG1 X", 0) == 0);
  CHECK(only_arcs.out.find("G2") == std::string::npos);
}

TEST_CASE("max-rate and baud: the line rate wins and is said once", "[gc-subdivide]") {
  std::string text = head_of("prusa_pegs_0.2_klipper_zhop_labels.gcode", 3000);
  // 115200 baud: 384 lines/s; travel at 180 mm/s then needs 0.47 mm pieces.
  auto r = run(gctest::tool_command("gc-subdivide", "--max 0.2 --baud 115200"), text);
  REQUIRE(r.status == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find("--max-rate") != std::string::npos);
  gctest::SubdivideLimits l = max_limits(0.2);
  l.rate = 115200.0 / 10 / 30;
  CHECK(gctest::check_subdivision(text, r.out, l).first_failure() == "");
  auto same = run(gctest::tool_command("gc-subdivide", "--max 0.2 --max-rate 384"), text);
  CHECK(same.out == r.out);
}

TEST_CASE("junk passes through unchanged with warnings", "[gc-subdivide][junk]") {
  std::string junk = "G1 X0 Y0 F600\nG1 X1e309 Y5\nG1 XNaN\nG1 X1e300\nG1 X0 Y0\n\x01\x02\xff\n" +
                     std::string(300000, 'G') + "\nG1 X" + std::string(5000, '7') + "\nG1 X3 Y4 ; fine\n";
  auto r = run(gctest::tool_command("gc-subdivide", "--max 0.5"), junk);
  CHECK(r.status == 0);
  CHECK(r.err.find("warning") != std::string::npos);
  std::vector<std::string> in = gctest::split_lines(junk), out = gctest::split_lines(r.out);
  REQUIRE(out.size() == in.size() - 1 + 11);  // 5 mm: 11 pieces of 0.455 mm
  CHECK(std::equal(in.begin(), in.end() - 1, out.begin()));
  auto quiet = run(gctest::tool_command("gc-subdivide", "-q --max 0.5"), junk);
  CHECK(quiet.err == "");
  CHECK(quiet.out == r.out);
}

TEST_CASE("files: output file and in-place and a missing file", "[gc-subdivide]") {
  std::string dir = gctest::temp_dir();
  std::string in = dir + "/in.gcode", out = dir + "/out.gcode";
  std::string text = head_of("slic3r_cube_0.2_abs_reprap_skirt.gcode", 800);
  gctest::write_file(in, text);
  auto piped = run(gctest::tool_command("gc-subdivide", "--max 1 " + quote(in)));
  REQUIRE(piped.status == 0);
  CHECK(run(gctest::tool_command("gc-subdivide", "--max 1 -o " + quote(out) + " " + quote(in))).status == 0);
  CHECK(read_file(out) == piped.out);
  CHECK(run(gctest::tool_command("gc-subdivide", "--max 1 -i " + quote(in))).status == 0);
  CHECK(read_file(in) == piped.out);
  auto missing = run(gctest::tool_command("gc-subdivide", "--max 1 " + quote(dir + "/none.gcode")));
  CHECK(missing.status == 1);
  CHECK(missing.err.rfind("gc-subdivide: ", 0) == 0);
}

TEST_CASE("usage errors exit 2 with a message", "[gc-subdivide][usage]") {
  for (const char* args : {"", "--max 0.2 --latency 1", "--max 0.05 --min 0.05", "--max -1", "--max 0.2 --layers x",
                           "--max 0.2 --arcs maybe", "--latency 1 --buffer 0", "--max 0.2 --z-range a:b",
                           "--max 0.2 -i", "--no-such-option"}) {
    INFO(args);
    auto r = run(gctest::tool_command("gc-subdivide", args), "G1 X1\n");
    CHECK(r.status == 2);
    CHECK(r.err.find("gc-subdivide") != std::string::npos);
    CHECK(r.out == "");
  }
  CHECK(run(gctest::tool_command("gc-subdivide", "--version")).out.rfind("gc-subdivide ", 0) == 0);
}

TEST_CASE("help and the man page name the same options", "[gc-subdivide][docs]") {
  auto help = run(gctest::tool_command("gc-subdivide", "--help"));
  REQUIRE(help.status == 0);
  std::string man = read_file(std::string(GC_FIXTURES_DIR) + "/../../man/gc-subdivide.1");
  std::set<std::string> in_help = gctest::long_options(help.out), in_man = gctest::long_options(man);
  CHECK(in_help == in_man);
  CHECK(in_help.count("--latency") == 1);
  CHECK(in_help.count("--no-travel") == 1);
}
