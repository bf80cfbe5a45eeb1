#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/core/number.hpp"
#include "gcode/transform/subdivide.hpp"
#include "subdivide_check.hpp"
#include "test_support.hpp"

using gcode::SubdivideOptions;

namespace {

struct Result {
  std::string out;
  gcode::SubdivideStats stats;
  std::uint64_t warnings = 0;
};

Result subdivide(std::string_view input, const SubdivideOptions& options) {
  gcode::Diagnostics diag("test", -1);
  gctest::Subdivided r = gctest::subdivide(input, options, &diag);
  return {r.text, r.stats, diag.warnings()};
}

SubdivideOptions max_of(double mm) {
  SubdivideOptions o;
  o.max_length = mm;
  o.min_length = std::min(0.05, mm / 2);
  return o;
}

gctest::SubdivideLimits limits_of(const SubdivideOptions& o) {
  gctest::SubdivideLimits l;
  l.max = o.max_length;
  l.latency = o.latency;
  l.buffer = o.buffer;
  l.rate = o.max_rate;
  l.min = o.min_length;
  l.travel = o.split_travel;
  l.arcs = o.split_arcs;
  return l;
}

// Runs the subdivider, then the independent checker, then a second pass that must change nothing.
std::string checked(std::string_view input, const SubdivideOptions& o) {
  Result r = subdivide(input, o);
  gctest::SubdivideCheck c = gctest::check_subdivision(input, r.out, limits_of(o));
  INFO(r.out);
  REQUIRE(c.first_failure() == "");
  CHECK(subdivide(r.out, o).out == r.out);
  return r.out;
}

std::vector<std::string> lines_of(const std::string& text) { return gctest::split_lines(text); }

}  // namespace

TEST_CASE("a long move becomes equal pieces ending on the input's own E text", "[subdivide]") {
  std::string out = checked("M82\nG1 X0 Y0 E0 F1200\nG1 X1 E.03333 ; wall\nM400\n", max_of(0.3));
  auto l = lines_of(out);
  REQUIRE(l.size() == 2 + 4 + 1);
  CHECK(l[2] == "G1 X0.25 E0.00833 ; wall\n");  // comment on the first piece only
  CHECK(l[3] == "G1 X0.5 E0.01667\n");
  CHECK(l[5] == "G1 X1 E.03333\n");           // last piece: the input's exact text
  CHECK(l[6] == "M400\n");
}

TEST_CASE("F is written on the first piece only, the mode stays", "[subdivide]") {
  std::string out = checked("G1 X0 Y0\nG1 F3000 X0.6 Y0.8\nG1 X0 Y0\n", max_of(0.4));
  auto l = lines_of(out);
  REQUIRE(l.size() == 1 + 3 + 3);
  CHECK(l[1] == "G1 F3000 X0.2 Y0.267\n");
  CHECK(l[2] == "G1 X0.4 Y0.533\n");
  CHECK(l[3] == "G1 X0.6 Y0.8\n");
  CHECK(l[4].find('F') == std::string::npos);
}

TEST_CASE("relative E pieces sum exactly at the written precision", "[subdivide]") {
  // 7 units of 1e-5 shared by 6 pieces: the remainder is carried, not lost.
  std::string out = checked("M83\nG1 X0 Y0\nG1 X1 E0.00007\n", max_of(0.2));
  auto l = lines_of(out);
  REQUIRE(l.size() == 2 + 6);
  long units = 0;
  for (std::size_t i = 2; i < l.size(); ++i) {
    std::string text = l[i].substr(0, l[i].size() - 1);  // the Line views into it
    gcode::Line p = gcode::Line::parse(text);
    REQUIRE(p.has('E'));
    CHECK(gcode::decimals_of(p.find('E')->raw) <= 5);
    units += std::lround(p.find('E')->value() * 1e5);
  }
  CHECK(units == 7);
  // Retraction moves (negative E while moving: a wipe) too.
  checked("M83\nG1 X5 Y5\nG1 X3 Y5 E-.7654\nG1 X3 Y3.5 E-.1\n", max_of(0.3));
}

TEST_CASE("G91 relative XYZ and the Marlin E coupling", "[subdivide]") {
  std::string out = checked("G90\nM82\nG1 X10 Y10 E1\nG91\nG1 X2.001 Y-1 E0.333\nG1 Z0.4\nG90\nG1 X0 E2\n",
                            max_of(0.5));
  gcode::MachineState s = gctest::replay_state(out);
  CHECK(s.position[gcode::kX] == 0);
  CHECK(s.position[gcode::kY] == Approx(9));
  CHECK(s.position[gcode::kE] == 2);
  CHECK(out.find("G1 Z0.4\n") != std::string::npos);  // pure Z: left alone
}

TEST_CASE("inches: pieces in inches with finer decimals and the limit in mm", "[subdivide]") {
  std::string out = checked("G20\nG90\nM82\nG1 X0 Y0 E0\nG1 X0.3937 Y0.1 E0.01 F600\nG21\nG1 X0 Y0\n", max_of(2));
  gcode::MachineState s = gctest::replay_state(out);
  CHECK_FALSE(s.inches);
  // 10.3 mm at 2 mm a piece: 6 pieces in inches.
  CHECK(gctest::check_subdivision("G20\nG90\nM82\nG1 X0 Y0 E0\nG1 X0.3937 Y0.1 E0.01 F600\n",
                                  subdivide("G20\nG90\nM82\nG1 X0 Y0 E0\nG1 X0.3937 Y0.1 E0.01 F600\n", max_of(2)).out,
                                  limits_of(max_of(2)))
            .pieces == 6);
}

TEST_CASE("G92 in the middle of a file: absolute E restarts from the new origin", "[subdivide]") {
  std::string out =
      checked("M82\nG1 X0 Y0 E5 F1200\nG1 X3 E6.5\nG92 E0\nG1 X0 E0.75\nG92 X100\nG1 X101.5 E1\n", max_of(0.5));
  auto l = lines_of(out);
  CHECK(std::find(l.begin(), l.end(), "G92 E0\n") != l.end());
  CHECK(std::find(l.begin(), l.end(), "G1 X0 E0.75\n") != l.end());
  CHECK(std::find(l.begin(), l.end(), "G1 X100.375 E0.8125\n") != l.end());
}

TEST_CASE("arcs: I/J and R forms clockwise and counter-clockwise and full circles", "[subdivide][arc]") {
  SubdivideOptions o = max_of(0.5);
  std::string ij = checked("G90\nM82\nG1 X10 Y0 E0 F1800\nG3 X0 Y10 I-10 J0 E2\nG2 X10 Y0 I0 J-10 E4\n", o);
  std::string r = checked("G90\nM82\nG1 X10 Y0 E0 F1800\nG3 X0 Y10 R10 E2\nG2 X10 Y0 R-10 E4\n", o);
  std::string full = checked("G90\nM83\nG1 X10 Y0 F1800\nG2 I-10 J0 E3.14159 ; circle\nG3 X10 Y0 I-10 E1\n", o);
  std::string helix = checked("G91\nG1 X10 Y0 F1800\nG3 I-10 J0 Z1 E2\nG90\n", o);
  // Quarter circle of radius 10 is 15.7 mm: at most 0.5 mm a chord.
  gctest::SubdivideCheck c = gctest::check_subdivision(
      "G90\nM82\nG1 X10 Y0 E0 F1800\nG3 X0 Y10 I-10 J0 E2\n",
      subdivide("G90\nM82\nG1 X10 Y0 E0 F1800\nG3 X0 Y10 I-10 J0 E2\n", o).out, limits_of(o));
  CHECK(c.arcs == 1);
  CHECK(c.pieces >= 32);
  CHECK(ij.find("G2") == std::string::npos);
  CHECK(r.find("G3") == std::string::npos);
  CHECK(std::count(full.begin(), full.end(), ';') == 1);
  CHECK(full.find("E0.02474 ; circle\n") != std::string::npos);  // 3.14159 / 127 chords
  CHECK(helix.find("G3") == std::string::npos);

  SECTION("the tolerance bounds the chord angle when no limit applies") {
    SubdivideOptions arcs_only;
    arcs_only.arc_tolerance = 0.01;
    std::string out = subdivide("G1 X10 Y0\nG2 I-10 J0\n", arcs_only).out;
    // r(1 - cos(t/2)) <= 0.01 for r = 10 needs t <= 0.0894 rad: 71 chords for 2 pi.
    CHECK(lines_of(out).size() == 1 + 71);
    gctest::SubdivideLimits l;
    CHECK(gctest::check_subdivision("G1 X10 Y0\nG2 I-10 J0\n", out, l).ok());
  }
  SECTION("Marlin's P turns are cut like the rest of the sweep") {
    std::string in = "G90\nM83\nG1 X10 Y0 F1800\nG2 I-10 J0 P1 Z0.4 E6.28318 ; two turns\n";
    std::string out = checked(in, o);
    // 2 turns of radius 10 are 125.7 mm: at least 252 chords of at most 0.5 mm.
    CHECK(lines_of(out).size() >= 3 + 252);
    CHECK(out.find(" P") == std::string::npos);
    CHECK(out.find("Z0.4") != std::string::npos);
  }
  SECTION("--arcs keep leaves them alone") {
    SubdivideOptions keep = max_of(0.5);
    keep.split_arcs = false;
    std::string in = "G92 X10 Y0\nG2 I-10 J0\n";
    CHECK(subdivide(in, keep).out == in);
  }
}

TEST_CASE("left alone: pure Z and pure E moves and firmware retraction and short moves and other words", "[subdivide]") {
  std::string in =
      "G1 X0 Y0 F600\nG1 Z5\nG1 E-2\nG10\nG11\nG1 X0.1 Y0.1\nN12 G1 X20*99\nG1 X40 S100\nG1 X60 A3\nG4 P100\n";
  Result r = subdivide(in, max_of(0.2));
  CHECK(r.out == in);
  CHECK(r.stats.moves_split == 0);
}

TEST_CASE("without travel splitting travel stays whole and extrusion is split", "[subdivide]") {
  SubdivideOptions o = max_of(0.5);
  o.split_travel = false;
  std::string out = checked("M83\nG0 X10 Y10 F6000\nG1 X12 Y10 E0.1\n", o);
  auto l = lines_of(out);
  CHECK(l[1] == "G0 X10 Y10 F6000\n");
  CHECK(l.size() == 2 + 5);
}

TEST_CASE("line endings: CRLF kept on every piece, a missing final newline stays missing", "[subdivide]") {
  std::string out = checked("G1 X0 Y0\r\nG1 X1 Y0\r\nG1 X0 Y0", max_of(0.4));
  auto l = lines_of(out);
  REQUIRE(l.size() == 1 + 3 + 3);
  for (std::size_t i = 0; i + 1 < l.size(); ++i) CHECK(l[i].substr(l[i].size() - 2) == "\r\n");
  CHECK(l.back() == "G1 X0 Y0");
  CHECK(lines_of(checked("G1 X0 Y0\nG1 X1 Y0", max_of(0.4))).back() == "G1 X1 Y0");
}

TEST_CASE("junk passes through unchanged with a warning and never a crash", "[subdivide]") {
  std::string huge = "G1 X" + std::string(100000, '9') + "\n";
  std::string in = "G1 X0 Y0 E0 F600\nG1 X1e309 Y5\nG1 XNaN Y2\nG1 X1e300 Y1\nG1 X0 Y0\nG1 X5 ~#\x01\n" + huge +
                   std::string(2000, 'G') + "\nG1 X2 Y2\n";
  Result r = subdivide(in, max_of(0.2));
  INFO(r.out.substr(0, 400));
  CHECK(r.warnings >= 3);
  // Every junk line is still there, byte for byte.
  for (const std::string& line : lines_of(in))
    if (line != "G1 X2 Y2\n") CHECK(r.out.find(line) != std::string::npos);
}

TEST_CASE("the piece limit from max or latency and buffer and rate and the min floor", "[subdivide]") {
  SubdivideOptions o;
  o.max_length = 0.2;
  CHECK(o.piece_limit(1800) == 0.2);
  o.max_length = 0;
  o.latency = 0.25;
  o.buffer = 20;
  CHECK(o.piece_limit(3000) == Approx(50.0 * 0.25 / 20));  // 50 mm/s: 0.625 mm
  CHECK(o.piece_limit(600) == Approx(0.125));
  CHECK(o.piece_limit(60) == Approx(0.1));                // floored at twice --min
  CHECK(o.piece_limit(0) == 0);                            // no feed rate yet: no time budget
  o.max_rate = 40;                                         // 40 lines/s < 20 / 0.25 = 80
  bool rate_won = false;
  CHECK(o.piece_limit(3000, &rate_won) == Approx(50.0 / 40));
  CHECK(rate_won);
}

TEST_CASE("the line rate wins over the length limit and is said once", "[subdivide]") {
  SubdivideOptions o = max_of(0.2);
  o.max_rate = 100;  // 100 mm/s at 100 lines/s: 1 mm pieces
  gcode::Diagnostics diag("test", -1);
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers, gcode::PipelineOptions{.layers = false});
  gcode::Subdivider s(o, pipeline.precision(), &diag);
  pipeline.add(s);
  gctest::run_stages(pipeline, "G1 X0 Y0 F6000\nG1 X10\nG1 X0\n");
  CHECK(diag.warnings() == 1);
  CHECK(s.stats().pieces == 2 * 11);
}

TEST_CASE("options that make no sense are refused", "[subdivide]") {
  SubdivideOptions o;
  o.max_length = 0.2;
  o.latency = 1;
  CHECK_THROWS_AS(o.validate(), std::invalid_argument);
  o.latency = 0;
  o.min_length = 0.2;
  CHECK_THROWS_WITH(o.validate(), Catch::Contains("twice --min"));
  o.min_length = 0.05;
  o.buffer = 0;
  CHECK_THROWS_AS(o.validate(), std::invalid_argument);
  o.buffer = 20;
  o.arc_tolerance = 0;
  CHECK_THROWS_AS(o.validate(), std::invalid_argument);
  o.arc_tolerance = 0.01;
  CHECK_NOTHROW(o.validate());
}

TEST_CASE("fixtures: a cut of the first layers at 0.1 mm passes the checker", "[subdivide][fixture]") {
  for (const char* name : {"prusa_cube_0.2_mk3s_rel_zhop.gcode", "cura_cube_0.2_abs_zhop_skirt.gcode",
                           "slic3r_cube_0.2_abs_reprap_skirt.gcode"}) {
    std::string text = gctest::read_file(gctest::fixture_path(name));
    text = text.substr(0, text.find('\n', 60000) + 1);
    INFO(name);
    Result r = subdivide(text, max_of(0.1));
    CHECK(r.warnings == 0);
    gctest::SubdivideCheck c = gctest::check_subdivision(text, r.out, limits_of(max_of(0.1)));
    CHECK(c.first_failure() == "");
    CHECK(c.pieces > 1000);
    CHECK(subdivide(r.out, max_of(0.1)).out == r.out);
  }
}
