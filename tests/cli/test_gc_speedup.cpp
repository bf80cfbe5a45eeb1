// gc-speedup on real slicer output, checked by the independent replay
// checker (tests/support/speed_check.hpp): every changed move at exactly
// factor x its original F (capped where caps apply), every other move at its
// original F across both region boundaries, positions and E unchanged, other
// lines byte for byte; selections, caps, ramps, the M220 route, idempotence,
// errors, and --help against the man page.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <set>

#include "gcode/core/feature.hpp"
#include "speed_check.hpp"
#include "test_support.hpp"

using gctest::fixture_path;
using gctest::quote;
using gctest::read_file;
using gctest::run;

namespace {

auto speedup(const std::string& args, std::string_view input = {}) {
  return run(gctest::tool_command("gc-speedup", args), input);
}

// The checker's per-line factors: `factor` where `in` says so, 0 elsewhere.
template <typename In>
gctest::SpeedRule rule_where(const gctest::LinePlace& place, double factor, In in) {
  gctest::SpeedRule r;
  for (std::size_t i = 0; i < place.layer.size(); ++i) r.factor.push_back(in(i) ? factor : 0.0);
  return r;
}

int layers_of(const gctest::LinePlace& place) { return *std::max_element(place.layer.begin(), place.layer.end()); }

// Runs the tool on `input` (stdin) and checks the output against `rule`.
gctest::SpeedCheck run_checked(const std::string& input, const std::string& args, const gctest::SpeedRule& rule) {
  auto r = speedup(args, input);
  INFO(args);
  INFO(r.err);
  REQUIRE(r.status == 0);
  gctest::SpeedCheck c = gctest::check_speed(input, r.out, rule);
  CHECK(c.first_failure() == "");
  return c;
}

}  // namespace

TEST_CASE("speedup factor 3 and 0.5 over the middle third of the layers of every fixture hold the checker",
          "[gc-speedup][fixtures]") {
  std::size_t inherited_in = 0, inherited_out = 0;
  for (const std::string& name : gctest::fixture_names()) {
    INFO(name);
    std::string text = read_file(fixture_path(name));
    gctest::LinePlace place = gctest::places_of(text);
    int n = layers_of(place), first = n / 3 + 1, last = 2 * n / 3;
    std::string range = std::to_string(first) + "-" + std::to_string(last);
    auto in = [&](std::size_t i) { return place.layer[i] >= first && place.layer[i] <= last; };
    for (double factor : {3.0, 0.5}) {
      std::string args = "--factor " + std::string(factor == 3 ? "3" : "0.5") + " --layers " + range;
      gctest::SpeedCheck c = run_checked(text, args, rule_where(place, factor, in));
      CHECK(c.changed > 100);
      CHECK(c.capped == 0);
      CHECK(c.marked > 0);
      inherited_in += c.inherited_in;
      inherited_out += c.inherited_out;
    }
  }
  // Moves without an F word on both sides of the boundaries were checked.
  CHECK(inherited_in > 100);
  CHECK(inherited_out > 10);
}

TEST_CASE("speedup without a region changes every layer and start and end code keep their speed", "[gc-speedup][fixtures]") {
  for (const char* name : {"cura_pegs_0.2_rel_fwretract.gcode", "prusa_dome_varlayer_ender3_abs.gcode",
                           "slic3r_cylinder_0.3_rel_zhop_brim.gcode"}) {
    INFO(name);
    std::string text = read_file(fixture_path(name));
    gctest::LinePlace place = gctest::places_of(text);
    gctest::SpeedCheck c = run_checked(text, "--factor 1.5", rule_where(place, 1.5, [&](std::size_t i) {
                                         return place.layer[i] > 0;
                                       }));
    CHECK(c.changed > 1000);
  }
}

TEST_CASE("speedup types change only those features on Cura and Prusa files also with layers", "[gc-speedup][fixtures][types]") {
  struct Case {
    const char* file;
    const char* types;
    const char* feature;  // the file's own name
  };
  std::size_t inherited = 0;
  for (const Case& k : {Case{"cura_cube_0.2_abs_zhop_skirt.gcode", "WALL-OUTER", "WALL-OUTER"},
                        Case{"cura_pegs_0.2_rel_fwretract.gcode", "fill", "FILL"},
                        Case{"prusa_cube_0.2_mk3s_rel_zhop.gcode", "'External perimeter'", "External perimeter"},
                        Case{"prusa_tshape_0.2_support_mk3s_brim.gcode", "WALL-OUTER", "External perimeter"},
                        Case{"prusa_tshape_0.2_support_mk3s_brim.gcode", "support", "Support material"}}) {
    INFO(k.file << " --types " << k.types);
    std::string text = read_file(fixture_path(k.file));
    gctest::LinePlace place = gctest::places_of(text);
    std::string feature = k.feature;
    gctest::SpeedCheck c = run_checked(text, std::string("--factor 3 --types ") + k.types,
                                       rule_where(place, 3, [&](std::size_t i) { return place.feature[i] == feature; }));
    CHECK(c.changed > 100);
    inherited += c.inherited_out + c.inherited_in;
    gctest::SpeedCheck both =
        run_checked(text, std::string("--factor 0.5 --layers 5-9 --types ") + k.types, rule_where(place, 0.5, [&](std::size_t i) {
                      return place.feature[i] == feature && place.layer[i] >= 5 && place.layer[i] <= 9;
                    }));
    CHECK(both.changed > 5);
    CHECK(both.changed < c.changed);
  }
  // Feature boundaries inside a layer, where the next feature inherits F.
  CHECK(inherited > 100);
}

TEST_CASE("speedup z-range selects layers by height", "[gc-speedup][fixtures]") {
  std::string text = read_file(fixture_path("prusa_dome_varlayer_ender3_abs.gcode"));
  gctest::LinePlace place = gctest::places_of(text);
  gctest::SpeedCheck c = run_checked(text, "--factor 2 --z-range 3:6", rule_where(place, 2, [&](std::size_t i) {
                                       return place.layer[i] > 0 && place.layer_z[i] >= 3 - 1e-6 &&
                                              place.layer_z[i] <= 6 + 1e-6;
                                     }));
  CHECK(c.changed > 100);
}

TEST_CASE("speedup max-flow keeps every changed move within the cap on every fixture and says so once", "[gc-speedup][fixtures][caps]") {
  for (const std::string& name : gctest::fixture_names()) {
    INFO(name);
    std::string text = read_file(fixture_path(name));
    gctest::LinePlace place = gctest::places_of(text);
    gctest::SpeedRule rule = rule_where(place, 3, [&](std::size_t i) { return place.layer[i] > 0; });
    rule.max_flow = 8;
    auto r = speedup("--factor 3 --max-flow 8", text);
    REQUIRE(r.status == 0);
    gctest::SpeedCheck c = gctest::check_speed(text, r.out, rule);
    CHECK(c.first_failure() == "");
    CHECK(c.capped > 10);
    CHECK(c.changed > 100);
    // One line about the caps (and, for a file without a diameter, one about that).
    CHECK(r.err.find("moves capped: ") != std::string::npos);
    CHECK(r.err.find("by --max-flow 8 mm3/s (filament 1.75 mm)") != std::string::npos);
    std::string err = gctest::without_e_mode_warning(r.err);
    std::size_t lines = static_cast<std::size_t>(std::count(err.begin(), err.end(), '\n'));
    CHECK(lines == (name.rfind("cura", 0) == 0 ? 2u : 1u));
  }
}

TEST_CASE("speedup max-speed and min-speed and a thicker filament keep moves within the caps and never turn the change around", "[gc-speedup][caps]") {
  std::string text = read_file(fixture_path("prusa_tshape_0.2_support_mk3s_brim.gcode"));
  gctest::LinePlace place = gctest::places_of(text);
  auto all = [&](std::size_t i) { return place.layer[i] > 0; };
  gctest::SpeedRule fast = rule_where(place, 3, all);
  fast.max_speed = 100;
  gctest::SpeedCheck c = run_checked(text, "--factor 3 --max-speed 100", fast);
  CHECK(c.capped > 100);
  gctest::SpeedRule slow = rule_where(place, 0.25, all);
  slow.min_speed = 15;
  slow.max_speed = 40;
  CHECK(run_checked(text, "--factor 0.25 --min-speed 15 --max-speed 40", slow).capped > 100);
  gctest::SpeedRule thick = rule_where(place, 2, all);
  thick.max_flow = 10;
  thick.filament = 2.85;
  CHECK(run_checked(text, "--factor 2 --max-flow 10 --filament-diameter 2.85", thick).capped > 100);
}

TEST_CASE("speedup ramp runs the first layer of the region at F1 and the last at F2 and linearly between", "[gc-speedup][ramp]") {
  for (const char* name : {"cura_pegs_0.2_rel_fwretract.gcode", "prusa_cube_0.2_mk3s_rel_zhop.gcode"}) {
    INFO(name);
    std::string text = read_file(fixture_path(name));
    gctest::LinePlace place = gctest::places_of(text);
    const int first = 10, last = 30;
    auto factor_at = [&](int layer) { return 2.0 + 1.0 * (layer - first) / (last - first); };
    // Exactly F1 and F2 on the end layers.
    gctest::SpeedRule ends = rule_where(place, 1, [&](std::size_t i) { return place.layer[i] == first || place.layer[i] == last; });
    for (std::size_t i = 0; i < ends.factor.size(); ++i)
      if (ends.factor[i] > 0) ends.factor[i] = factor_at(place.layer[i]);
    auto r = speedup("--ramp 2:3 --layers 10-30", text);
    REQUIRE(r.status == 0);
    // The end layers, and every layer in between within the rounding of its factor.
    gctest::SpeedRule between = rule_where(place, 1, [&](std::size_t i) { return place.layer[i] >= first && place.layer[i] <= last; });
    for (std::size_t i = 0; i < between.factor.size(); ++i)
      if (between.factor[i] > 0) between.factor[i] = factor_at(place.layer[i]);
    between.slack = 1e-3;
    gctest::SpeedCheck c = gctest::check_speed(text, r.out, between);
    CHECK(c.first_failure() == "");
    // The end layers exactly: checked with the rule that leaves the inner layers out.
    std::string only_ends;
    std::vector<std::string> in = gctest::split_lines(text), out = gctest::split_lines(r.out);
    for (std::size_t i = 0; i < in.size(); ++i)
      only_ends += (place.layer[i] > first && place.layer[i] < last) ? in[i] : out[i];
    CHECK(gctest::check_speed(text, only_ends, ends).first_failure() == "");
    CHECK(r.out.find("; gc-speedup x2.5\n") != std::string::npos);  // layer 20: the middle
  }
}

TEST_CASE("speedup speed sets one speed for every changed move and travel options add travel moves", "[gc-speedup]") {
  std::string text = read_file(fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode"));
  gctest::LinePlace place = gctest::places_of(text);
  auto in = [&](std::size_t i) { return place.layer[i] >= 3 && place.layer[i] <= 8; };
  gctest::SpeedRule s = rule_where(place, 1, in);
  s.speed = 40;
  CHECK(run_checked(text, "--speed 40 --layers 3-8", s).changed > 100);
  gctest::SpeedRule t = rule_where(place, 2, in);
  t.travel = true;
  gctest::SpeedCheck with_travel = run_checked(text, "--factor 2 --travel --layers 3-8", t);
  gctest::SpeedRule tf = rule_where(place, 2, in);
  tf.travel_factor = 1.5;
  gctest::SpeedCheck travel_factor = run_checked(text, "--factor 2 --travel-factor 1.5 --layers 3-8", tf);
  gctest::SpeedCheck without = run_checked(text, "--factor 2 --layers 3-8", rule_where(place, 2, in));
  CHECK(with_travel.changed > without.changed + 50);
  CHECK(travel_factor.changed == with_travel.changed);
}

TEST_CASE("speedup keeps CRLF endings and a missing final newline", "[gc-speedup]") {
  std::string text = gctest::head_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 1500);
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  crlf.resize(crlf.size() - 2);
  gctest::LinePlace place = gctest::places_of(crlf);
  gctest::SpeedCheck c = run_checked(crlf, "--factor 3", rule_where(place, 3, [&](std::size_t i) { return place.layer[i] > 0; }));
  CHECK(c.changed > 100);
  auto r = speedup("--factor 3", crlf);
  CHECK(r.out.substr(r.out.size() - 2) != "\r\n");
  for (const std::string& l : gctest::split_lines(r.out.substr(0, r.out.rfind('\n') + 1)))
    REQUIRE(l.substr(l.size() - 2) == "\r\n");
}

TEST_CASE("speedup writes the same bytes to a pipe and an output file and in place", "[gc-speedup]") {
  std::string dir = gctest::temp_dir();
  std::string in = dir + "/in.gcode", out = dir + "/out.gcode";
  std::string text = gctest::head_of("slic3r_cube_0.2_abs_reprap_skirt.gcode", 1500);
  gctest::write_file(in, text);
  auto piped = speedup("--factor 2 --layers 2-4", text);
  REQUIRE(piped.status == 0);
  CHECK(piped.out != text);
  CHECK(speedup("--factor 2 --layers 2-4 -o " + quote(out) + " " + quote(in)).status == 0);
  CHECK(read_file(out) == piped.out);
  CHECK(speedup("--factor 2 --layers 2-4 -i " + quote(in)).status == 0);
  CHECK(read_file(in) == piped.out);
  auto missing = speedup("--factor 2 " + quote(dir + "/none.gcode"));
  CHECK(missing.status == 1);
  CHECK(missing.err.rfind("gc-speedup: ", 0) == 0);
}

TEST_CASE("speedup refuses a second run over a changed region unless forced and then the factors multiply", "[gc-speedup][marks]") {
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/part.gcode";
  std::string text = read_file(fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode"));
  auto once = speedup("--factor 2 --layers 5-10", text);
  REQUIRE(once.status == 0);
  gctest::write_file(file, once.out);
  // Refused: exit 1, the file untouched.
  auto again = speedup("--factor 2 --layers 8-12 -i " + quote(file));
  CHECK(again.status == 1);
  CHECK(again.err.find("already changed by gc-speedup") != std::string::npos);
  CHECK(again.err.find("--force") != std::string::npos);
  CHECK(read_file(file) == once.out);
  // A region that does not overlap is fine.
  CHECK(speedup("--factor 2 --layers 12-14", once.out).status == 0);
  // --force: layers 8-10 run at 4x, 11-12 at 2x.
  auto forced = speedup("--factor 2 --layers 8-12 --force", once.out);
  REQUIRE(forced.status == 0);
  gctest::LinePlace place = gctest::places_of(text);
  gctest::SpeedRule rule = rule_where(place, 2, [&](std::size_t i) { return place.layer[i] >= 5 && place.layer[i] <= 12; });
  for (std::size_t i = 0; i < rule.factor.size(); ++i)
    if (place.layer[i] >= 8 && place.layer[i] <= 10) rule.factor[i] = 4;
  CHECK(gctest::check_speed(text, forced.out, rule).first_failure() == "");
}

TEST_CASE("speedup m220 puts the firmware factor at the region start and its restore after it with B and R on Marlin 2", "[gc-speedup][m220]") {
  std::string cura = read_file(fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode"));
  auto r = speedup("--factor 1.5 --layers 3-4 --m220", cura);
  REQUIRE(r.status == 0);
  std::vector<std::string> out = gctest::split_lines(r.out), in = gctest::split_lines(cura);
  REQUIRE(out.size() == in.size() + 2);
  std::vector<std::string> added;
  for (const std::string& l : out)
    if (l.rfind("M220", 0) == 0) added.push_back(l);
  CHECK(added == std::vector<std::string>{"M220 S150 ; gc-speedup x1.5\n", "M220 S100 ; gc-speedup restore\n"});
  // Apart from the two lines, the output is the input.
  std::vector<std::string> rest;
  for (const std::string& l : out)
    if (l.rfind("M220", 0) != 0) rest.push_back(l);
  CHECK(rest == in);
  // The factor goes in before the first move of layer 3, the restore before the first move of layer 5.
  gctest::LinePlace place = gctest::places_of(cura);
  std::size_t start = std::find(out.begin(), out.end(), added[0]) - out.begin();
  std::size_t end = std::find(out.begin(), out.end(), added[1]) - out.begin();
  CHECK(place.layer[start] == 3);  // out[start] is the input line `start` moved down by one
  CHECK(place.layer[end - 1] == 5);
  std::vector<gctest::ReplayedMove> moves = gctest::replay_moves(cura);
  auto first_move_of = [&](int layer) {
    for (const auto& m : moves)
      if (place.layer[m.line_index] == layer) return m.line_index;
    return std::size_t{0};
  };
  CHECK(start == first_move_of(3));
  CHECK(end == first_move_of(5) + 1);

  std::string prusa = read_file(fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode"));
  auto b = speedup("--ramp 1.5:2.5 --layers 3-5 --m220 -v", prusa);
  REQUIRE(b.status == 0);
  std::vector<std::string> lines;
  for (const std::string& l : gctest::split_lines(b.out))
    if (l.rfind("M220", 0) == 0) lines.push_back(l);
  CHECK(lines == std::vector<std::string>{"M220 B ; gc-speedup x1.5\n", "M220 S150 ; gc-speedup x1.5\n",
                                          "M220 S200 ; gc-speedup x2\n", "M220 S250 ; gc-speedup x2.5\n",
                                          "M220 R ; gc-speedup restore\n"});
  CHECK(b.err.find("estimated print time") != std::string::npos);
  // Whole percents only, and said so.
  auto odd = speedup("--factor 1.333 --layers 3 --m220", cura);
  CHECK(odd.out.find("M220 S133 ; gc-speedup x1.333\n") != std::string::npos);
  CHECK(odd.err.find("whole percents; x1.333 is written M220 S133") != std::string::npos);
  auto reset = speedup("--factor 2 --layers 3 --m220 --m220-restore reset", prusa);
  CHECK(reset.out.find("M220 S100 ; gc-speedup restore") != std::string::npos);
  CHECK(reset.out.find("M220 B") == std::string::npos);
}

TEST_CASE("speedup verbose gives the estimated time before and after per layer of the region and in total", "[gc-speedup][time]") {
  std::string text = read_file(fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode"));
  auto r = speedup("--factor 2 --layers 10-12 -v", text);
  REQUIRE(r.status == 0);
  CHECK(r.err.find("gc-speedup: layer 10: ") != std::string::npos);
  CHECK(r.err.find("gc-speedup: layer 12: ") != std::string::npos);
  CHECK(r.err.find("gc-speedup: layer 13: ") == std::string::npos);
  std::size_t at = r.err.find("estimated print time ");
  REQUIRE(at != std::string::npos);
  CHECK(r.err.find("(-", at) != std::string::npos);  // faster
  auto quiet = speedup("--factor 2 --layers 10-12", text);
  CHECK(quiet.err == "");
  CHECK(quiet.out == r.out);
}

TEST_CASE("speedup bad input gives a clear error and exit status 2 and leaves the file untouched", "[gc-speedup][usage]") {
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/part.gcode";
  std::string text = read_file(fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode"));
  gctest::write_file(file, text);
  struct Case {
    const char* args;
    const char* message;
  };
  for (const Case& k : {Case{"--factor 2 --types WALL-OUTR,FILL", "no feature 'WALL-OUTR' in the file; it has"},
                        Case{"--factor 2 --types bridge", "it has 'SKIRT', 'WALL-INNER', 'WALL-OUTER', 'SKIN', 'FILL'"},
                        Case{"--ramp 1:2 --types Ironing", "no feature 'Ironing'"},
                        Case{"--factor 2 --layers 9-5", "runs backwards"},
                        Case{"--factor 2 --layers ''", "--layers: empty"},
                        Case{"--factor 2 --z-range 5:2", "runs backwards"},
                        Case{"--factor 2 --types ''", "--types: empty"},
                        Case{"--factor 2 --types ,", "--types"},
                        Case{"--factor 0", "--factor"},
                        Case{"--factor -1", "--factor"},
                        Case{"--ramp 1:0", "--ramp"},
                        Case{"--ramp 2", "--ramp"},
                        Case{"--factor 2 --speed 40", "--factor excludes --speed"},
                        Case{"--speed 40 --ramp 1:2", "excludes"},
                        Case{"--layers 3", "give the change"},
                        Case{"--factor 2 --min-speed 50 --max-speed 40", "--min-speed 50 is above --max-speed 40"},
                        Case{"--factor 2 --m220 --max-flow 10", "--m220"},
                        Case{"--speed 50 --m220", "--m220"},
                        Case{"--factor 2 --m220 --travel", "--m220"},
                        Case{"--factor 2 --m220-restore backup", "--m220-restore goes with --m220"},
                        Case{"--factor 2 --m220 --m220-restore later", "--m220-restore"},
                        Case{"--factor 2 --travel --travel-factor 2", "excludes"},
                        Case{"--factor 2 --filament-diameter 0", "--filament-diameter"}}) {
    INFO(k.args);
    auto r = speedup(std::string(k.args) + " -i " + quote(file));
    CHECK(r.status == 2);
    CHECK(r.err.rfind("gc-speedup: ", 0) == 0);
    CHECK(r.err.find(k.message) != std::string::npos);
    CHECK(r.err.find("(see gc-speedup --help)") != std::string::npos);
    CHECK(read_file(file) == text);
    CHECK(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()) == 1);
  }
  // A file without ;TYPE: comments says so, before anything goes out: to
  // standard output from a pipe, nothing at all.
  auto none = speedup("--factor 2 --types FILL", read_file(fixture_path("slic3r_cube_0.2_abs_reprap_skirt.gcode")));
  CHECK(none.status == 2);
  CHECK(none.err.find("the file has no ;TYPE: comments") != std::string::npos);
  CHECK(none.out.empty());
  auto unknown = speedup("--factor 2 --types bridge", text);
  CHECK(unknown.status == 2);
  CHECK(unknown.err.find("no feature 'bridge'") != std::string::npos);
  CHECK(unknown.out.empty());
  auto named = speedup("--factor 2 --types bridge " + quote(file));
  CHECK(named.status == 2);
  CHECK(named.out.empty());
  CHECK(speedup("--version").out.rfind("gc-speedup ", 0) == 0);
}

TEST_CASE("speedup region the file does not have changes nothing and warns", "[gc-speedup]") {
  std::string text = read_file(fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode"));
  for (const char* args : {"--factor 3 --layers 500-600", "--factor 3 --z-range 100:", "--ramp 1:3 --layers 500-"}) {
    INFO(args);
    auto r = speedup(args, text);
    CHECK(r.status == 0);
    CHECK(r.out == text);
    CHECK(r.err.find("no layer of") != std::string::npos);
    CHECK(speedup(std::string(args) + " -q", text).err == "");
  }
  // Factor 1 changes nothing at all.
  CHECK(speedup("--factor 1", text).out == text);
}

TEST_CASE("speedup help and the man page name the same options", "[gc-speedup][docs]") {
  auto help = speedup("--help");
  REQUIRE(help.status == 0);
  std::string man = read_file(std::string(GC_FIXTURES_DIR) + "/../../man/gc-speedup.1");
  std::set<std::string> in_help = gctest::long_options(help.out), in_man = gctest::long_options(man);
  CHECK(in_help == in_man);
  CHECK(in_help.count("--m220-restore") == 1);
  CHECK(in_help.count("--max-flow") == 1);
}
