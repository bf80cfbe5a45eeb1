// gc-pause-at on every fixture: the output is replayed through MachineState
// next to the original, line by line, and the invariants of issue 4 are
// checked independently of the tool's own layer tracker (layers are counted
// from the slicer's markers, or from extrusion heights in unmarked files).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/machine_state.hpp"
#include "test_support.hpp"

using gctest::fixture_names;
using gctest::fixture_path;
using gctest::quote;
using gctest::read_file;
using gctest::run;
using gctest::split_lines;
using gctest::tool_path;

namespace {

const std::vector<int> kPauseLayers = {3, 10, 25};

std::string tool() { return quote(tool_path("gc-pause-at")); }

bool is_cura(const std::string& name) { return name.rfind("cura_", 0) == 0; }

// Cura's CLI output says nothing about the bed: those runs name it.
std::string bed_for(const std::string& name) { return is_cura(name) ? " --bed 220x220" : ""; }

std::string layer_list() {
  std::string s;
  for (int l : kPauseLayers) {
    if (!s.empty()) s += ',';
    s += std::to_string(l);
  }
  return s;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// The layer-marker comment this fixture uses, or "" for an unmarked file.
std::string marker_of(const std::string& text) {
  if (text.find("\n;LAYER_CHANGE") != std::string::npos) return ";LAYER_CHANGE";
  if (text.find("\n;LAYER:") != std::string::npos) return ";LAYER:";
  return "";
}

std::string strip(std::string line) {
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  return line;
}

struct Expect {
  double net = 0;                 // filament each block must push in total
  bool relative_file_no_m82 = true;
};

struct Block {
  std::size_t original_line = 0;  // 1-based input line the block precedes
  std::vector<std::string> lines;
  double net = 0;
  std::string park;               // "X.. Y.."
};

// Replays the original and the output side by side and checks (a)-(e).
std::vector<Block> check_output(const std::string& name, const std::string& original, const std::string& output,
                                const Expect& expect) {
  INFO(name);
  std::vector<std::string> in = split_lines(original);
  std::vector<std::string> out = split_lines(output);
  const std::string marker = marker_of(original);
  // With the slicer's own layer heights (tests/fixtures/expected), layers are
  // counted from them: an extrusion ending in (z[k-1], z[k]] is in layer k+1
  // (a spiral turn climbs through its band), after layer 1 has begun (a
  // start-code purge is no layer).
  std::vector<double> zs;
  if (auto e = gctest::expected_data(name); !e.is_null()) zs = e["z"].get<std::vector<double>>();
  int bands_started = 0, top_band = 0;
  std::vector<int> bands_at_block;
  auto band_of = [&zs](double z) {
    return static_cast<int>(std::lower_bound(zs.begin(), zs.end(), z - 1e-6) - zs.begin()) + 1;
  };

  // The print's XY box: every extrusion after the first layer marker (or,
  // unmarked, every extrusion but a purge line at the bed's edge: x or y < 10).
  double bx0 = 1e9, by0 = 1e9, bx1 = -1e9, by1 = -1e9;
  {
    gcode::MachineState s = gctest::initial_state(original);
    bool in_layers = marker.empty();
    for (const std::string& l : in) {
      if (!marker.empty() && starts_with(l, marker.c_str())) in_layers = true;
      gcode::Move m = s.apply(gcode::Line::parse(strip(l)));
      if (!in_layers || !m.extruding) continue;
      if (marker.empty() && (m.end[gcode::kX] < 10 || m.end[gcode::kY] < 10)) continue;
      for (const auto& p : {m.start, m.end}) {
        bx0 = std::min(bx0, p[gcode::kX]);
        by0 = std::min(by0, p[gcode::kY]);
        bx1 = std::max(bx1, p[gcode::kX]);
        by1 = std::max(by1, p[gcode::kY]);
      }
    }
  }

  gcode::MachineState sr = gctest::initial_state(original), so = sr;  // original, output
  std::vector<Block> blocks;
  std::size_t i = 0, j = 0;
  int markers_seen = 0;
  double top_z = 0, last_extrusion_z = -1;
  int z_levels = 0;  // distinct extrusion heights, for unmarked files
  std::vector<int> levels_at_block, markers_at_block;
  std::vector<double> last_z_at_block;
  std::vector<std::size_t> blocks_waiting_for_extrusion;
  while (i < out.size()) {
    if (starts_with(out[i], "; gc-pause-at: pause")) {
      // (e) the head is still where layer N-1's last extrusion left it.
      CHECK(so.position[gcode::kZ] == last_extrusion_z);
      Block b;
      b.original_line = j + 1;
      double before = so.filament_total;
      const bool rel_e = so.relative_e;
      gcode::MachineState start = so;
      for (++i; i < out.size() && !starts_with(out[i], "; gc-pause-at: end"); ++i) {
        std::string text = strip(out[i]);
        b.lines.push_back(text);
        gcode::Move m = so.apply(gcode::Line::parse(text));
        if (starts_with(text, "G1 X") && b.park.empty()) b.park = text.substr(3, text.find(" F") - 3);
        // Never a forced M82 in a relative file (Cura #5130).
        if (expect.relative_file_no_m82 && rel_e) CHECK(text != "M82");
        // (d) over the print, never below what is already printed.
        if (m.kind == gcode::MoveKind::Linear) {
          for (const auto& p : {m.start, m.end}) {
            bool over = p[gcode::kX] >= bx0 && p[gcode::kX] <= bx1 && p[gcode::kY] >= by0 && p[gcode::kY] <= by1;
            if (over) CHECK(p[gcode::kZ] >= std::min(top_z, start.position[gcode::kZ]) - 1e-9);
          }
          // XY travel happens only at a safe height, well above the print.
          if (m.xy_length > 0) CHECK(m.end[gcode::kZ] >= top_z + 1 - 1e-9);
          // Filament is pushed out only off the print (purge blobs, Cura #13317).
          if (m.filament > 0 && m.end[gcode::kX] != start.position[gcode::kX]) {
            bool over = m.end[gcode::kX] >= bx0 && m.end[gcode::kX] <= bx1 && m.end[gcode::kY] >= by0 &&
                        m.end[gcode::kY] <= by1;
            CHECK_FALSE(over);
          }
        }
      }
      REQUIRE(i < out.size());
      ++i;
      // (b) everything the following original lines rely on is restored
      // exactly (Cura #5924 resumed 1 mm high, #9430 at the wrong XY).
      CHECK(so.position[gcode::kX] == sr.position[gcode::kX]);
      CHECK(so.position[gcode::kY] == sr.position[gcode::kY]);
      CHECK(so.position[gcode::kZ] == sr.position[gcode::kZ]);
      // Absolute E: exactly; relative E: the running sum, to its float noise.
      if (!sr.relative_e) CHECK(so.position[gcode::kE] == sr.position[gcode::kE]);
      CHECK(so.position[gcode::kE] == Approx(sr.position[gcode::kE]).margin(1e-6));
      CHECK(so.relative_e == sr.relative_e);
      CHECK(so.relative_xyz == sr.relative_xyz);
      CHECK(so.feedrate == sr.feedrate);
      CHECK(so.firmware_retracted == sr.firmware_retracted);
      CHECK(so.hotend_target == sr.hotend_target);
      // (c) the block pushes exactly what was asked.
      b.net = so.filament_total - before;
      CHECK(b.net == Approx(expect.net).margin(1e-9));
      blocks.push_back(b);
      markers_at_block.push_back(markers_seen);
      levels_at_block.push_back(z_levels);
      bands_at_block.push_back(top_band);
      last_z_at_block.push_back(last_extrusion_z);
      blocks_waiting_for_extrusion.push_back(blocks.size() - 1);
      continue;
    }
    // (a) outside the blocks: the same bytes and the same moves. (Compared
    // without an assertion per line: Catch2 would count millions of them.)
    REQUIRE(j < in.size());
    if (out[i] != in[j]) REQUIRE(out[i] == in[j]);
    gcode::Line line = gcode::Line::parse(strip(out[i]));
    gcode::Move mo = so.apply(line);
    gcode::Move mr = sr.apply(line);
    bool same = mo.kind == mr.kind && mo.feedrate == mr.feedrate &&
                std::fabs(mo.filament - mr.filament) <= 1e-9 &&
                std::fabs(mo.end[gcode::kE] - mr.end[gcode::kE]) <= 1e-6;
    for (int a = 0; a < 3; ++a) same = same && mo.start[a] == mr.start[a] && mo.end[a] == mr.end[a];
    if (!same) {
      INFO("output line " << i + 1 << ": " << out[i]);
      CHECK(mo.kind == mr.kind);
      CHECK(mo.feedrate == mr.feedrate);
      CHECK(mo.filament == Approx(mr.filament).margin(1e-9));
      CHECK(mo.end[gcode::kE] == Approx(mr.end[gcode::kE]).margin(1e-6));
      for (int a = 0; a < 3; ++a) {
        CHECK(mo.start[a] == mr.start[a]);
        CHECK(mo.end[a] == mr.end[a]);
      }
    }
    if (!marker.empty() && starts_with(out[i], marker.c_str())) ++markers_seen;
    if (mr.extruding) {
      double z = mr.end[gcode::kZ];
      if (z_levels == 0 || std::fabs(mr.start[gcode::kZ] - last_extrusion_z) > 1e-6) ++z_levels;
      int band = zs.empty() ? 0 : band_of(z);
      if (band == 1) bands_started = 1;
      if (bands_started) top_band = std::max(top_band, band);
      // (e) the first extrusion after a pause is already in the next layer.
      for (std::size_t b : blocks_waiting_for_extrusion) {
        if (!zs.empty()) {
          CHECK(band > bands_at_block[b]);
        } else if (!marker.empty()) {
          CHECK(markers_seen > markers_at_block[b]);
        } else {
          CHECK(std::fabs(mr.start[gcode::kZ] - last_z_at_block[b]) > 1e-6);
        }
      }
      blocks_waiting_for_extrusion.clear();
      last_extrusion_z = z;
      top_z = std::max(top_z, z);
    }
    ++i;
    ++j;
  }
  CHECK(j == in.size());
  // (e) layer N's block comes after N-1 layers: counted from the markers
  // (Cura's ;LAYER:n, PrusaSlicer's ;LAYER_CHANGE) or from extrusion heights.
  REQUIRE(blocks.size() == kPauseLayers.size());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    if (!zs.empty()) {
      CHECK(bands_at_block[b] == kPauseLayers[b] - 1);
    } else if (!marker.empty()) {
      CHECK(markers_at_block[b] == kPauseLayers[b] - 1);
    } else {
      CHECK(levels_at_block[b] == kPauseLayers[b] - 1);
    }
  }
  return blocks;
}

struct DryRow {
  std::string layer, z;
  std::size_t line;
  std::string park;
};

std::vector<DryRow> parse_dry_run(const std::string& text) {
  std::vector<DryRow> rows;
  for (const std::string& l : split_lines(text)) {
    if (starts_with(l, "#")) continue;
    std::istringstream ss(strip(l));
    DryRow r;
    std::string px, py, pz;
    ss >> r.layer >> r.z >> r.line >> px >> py >> pz;
    r.park = px + " " + py;
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

TEST_CASE("gc-pause-at: defaults on every fixture keep moves, restore state, push nothing", "[gc-pause-at]") {
  for (const std::string& name : fixture_names()) {
    std::string path = fixture_path(name);
    std::string original = read_file(path);
    auto r = run(tool() + " --before-layer " + layer_list() + bed_for(name) + " " + quote(path));
    INFO(name << ": " << r.err);
    REQUIRE(r.status == 0);
    std::vector<Block> blocks = check_output(name, original, r.out, Expect{});
    // --dry-run lists exactly the places and park positions used.
    auto d = run(tool() + " --dry-run --before-layer " + layer_list() + bed_for(name) + " " + quote(path));
    REQUIRE(d.status == 0);
    std::vector<DryRow> rows = parse_dry_run(d.out);
    REQUIRE(rows.size() == blocks.size());
    for (std::size_t b = 0; b < rows.size(); ++b) {
      CHECK(rows[b].layer == std::to_string(kPauseLayers[b]));
      CHECK(rows[b].line == blocks[b].original_line);
      CHECK(rows[b].park == blocks[b].park);
    }
    // The default pause retracts unless the file already had, then waits with M0.
    for (const Block& b : blocks) CHECK(std::count_if(b.lines.begin(), b.lines.end(), [](const std::string& l) {
                                          return starts_with(l, "M0 Paused at layer");
                                        }) == 1);
  }
}

TEST_CASE("gc-pause-at: filament change with unload, reload, purge and prime on every fixture", "[gc-pause-at]") {
  for (const std::string& name : fixture_names()) {
    std::string path = fixture_path(name);
    std::string original = read_file(path);
    auto r = run(tool() + " --before-layer " + layer_list() + bed_for(name) +
                 " --retract 3 --lift 5 --min-park-z 30 --standby-temp 150 --unload 400 --reload 420"
                 " --purge 30 --prime 1.5 --beep --message 'Change colour at {layer}' --host-message paused"
                 " --stepper-hold 600 --wait-moves " +
                 quote(path));
    INFO(name << ": " << r.err);
    REQUIRE(r.status == 0);
    Expect e;
    e.net = -400 + 420 + 30 + 1.5;
    std::vector<Block> blocks = check_output(name, original, r.out, e);
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const auto& lines = blocks[b].lines;
      auto has = [&lines](const std::string& l) { return std::find(lines.begin(), lines.end(), l) != lines.end(); };
      CHECK(has("M0 Change colour at " + std::to_string(kPauseLayers[b])));
      CHECK(has("M104 S150"));
      CHECK(has("M118 paused"));
      CHECK(has("M84 S600"));
      CHECK(has("M400"));
      CHECK(has("M300 S440 P1000"));
      // The wait comes before heating back up, which comes before any reload.
      auto at = [&lines](const std::string& prefix) {
        for (std::size_t k = 0; k < lines.size(); ++k)
          if (starts_with(lines[k], prefix.c_str())) return static_cast<long>(k);
        return -1L;
      };
      CHECK(at("M0 ") < at("M109 "));
    }
  }
}

TEST_CASE("gc-pause-at: no single E move longer than 150 mm", "[gc-pause-at]") {
  std::string path = fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode");
  auto r = run(tool() + " --before-layer 5 --unload 620 --reload 640 " + quote(path));
  REQUIRE(r.status == 0);
  gcode::MachineState s;
  bool in_block = false;
  int e_moves = 0;
  for (const std::string& l : split_lines(r.out)) {
    if (starts_with(l, "; gc-pause-at: pause")) in_block = true;
    if (starts_with(l, "; gc-pause-at: end")) in_block = false;
    gcode::Move m = s.apply(gcode::Line::parse(strip(l)));
    if (in_block && m.filament != 0) {
      ++e_moves;
      CHECK(std::fabs(m.filament) <= 150 + 1e-9);
    }
  }
  CHECK(e_moves >= 10);
}

TEST_CASE("gc-pause-at: each --method writes its wait command", "[gc-pause-at]") {
  std::string path = fixture_path("slic3r_cube_0.2_abs_reprap_skirt.gcode");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"M0", "M0 Paused at layer 4"}, {"M1", "M1 Paused at layer 4"}, {"M25", "M25"},
      {"M125", "M125"},               {"M226", "M226"},               {"M600", "M600"},
      {"M601", "M601"},               {"@pause", "@pause"},           {"PAUSE", "PAUSE"},
      {"G4 --dwell 30", "G4 S30"},    {"'custom:M117 Insert nuts\\nM0'", "M117 Insert nuts|M0"},
  };
  for (const auto& [method, want] : cases) {
    auto r = run(tool() + " --before-layer 4 --method " + method + " " + quote(path));
    INFO(method << ": " << r.err);
    REQUIRE(r.status == 0);
    std::string block = r.out.substr(r.out.find("; gc-pause-at: pause"));
    block = block.substr(0, block.find("; gc-pause-at: resume"));
    std::string wanted = want;
    std::replace(wanted.begin(), wanted.end(), '|', '\n');
    CHECK(block.find("\n" + wanted + "\n") != std::string::npos);
  }
  // none: the block parks and returns, with no wait at all (gc-send waits).
  auto r = run(tool() + " --before-layer 4 --method none --message '' " + quote(path));
  REQUIRE(r.status == 0);
  std::string block = r.out.substr(r.out.find("; gc-pause-at: pause"));
  block = block.substr(0, block.find("; gc-pause-at: end"));
  for (const char* wait : {"M0", "M1", "M25", "M600", "@pause", "PAUSE", "G4", "M117"})
    CHECK(block.find(std::string("\n") + wait) == std::string::npos);
  // --before and --after custom code around the wait.
  r = run(tool() + " --before-layer 4 --before 'M117 before' --after 'M117 after\\nM118 back' " + quote(path));
  REQUIRE(r.status == 0);
  CHECK(r.out.find("M117 before\nM0 Paused at layer 4\n; gc-pause-at: resume\nM117 after\nM118 back\n") !=
        std::string::npos);
}

TEST_CASE("gc-pause-at: --z picks the first layer above the height, never a Z-hop (Cura #10242)", "[gc-pause-at]") {
  // Both files hop 0.4 mm: a hop from layer 4 (Z 0.8) reaches 1.2 > 1.1.
  for (const char* name : {"cura_cube_0.2_abs_zhop_skirt.gcode", "prusa_cube_0.2_mk3s_rel_zhop.gcode"}) {
    auto r = run(tool() + " --dry-run --z 1.1 --bed 220x220 " + quote(fixture_path(name)));
    INFO(name << r.err);
    REQUIRE(r.status == 0);
    std::vector<DryRow> rows = parse_dry_run(r.out);
    REQUIRE(rows.size() == 1);
    CHECK(rows[0].layer == "6");
    CHECK(rows[0].z == "1.2");
  }
}

TEST_CASE("gc-pause-at: --after-layer N equals --before-layer N+1, and --every, and after the last layer", "[gc-pause-at]") {
  std::string path = fixture_path("slic3r_cylinder_0.3_rel_zhop_brim.gcode");
  auto a = run(tool() + " --after-layer 7 " + quote(path));
  auto b = run(tool() + " --before-layer 8 " + quote(path));
  REQUIRE(a.status == 0);
  CHECK(a.out == b.out);
  auto e = run(tool() + " --dry-run --every 40 " + quote(path));
  REQUIRE(e.status == 0);
  std::vector<DryRow> rows = parse_dry_run(e.out);
  REQUIRE(rows.size() == 3);
  CHECK(rows[0].layer == "41");
  CHECK(rows[2].layer == "121");
  auto last = run(tool() + " --dry-run --after-layer 133 " + quote(path));
  REQUIRE(last.status == 0);
  rows = parse_dry_run(last.out);
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].layer == "end");
}

TEST_CASE("gc-pause-at: a pipe streams the same as a file, and without the bed it fails before writing", "[gc-pause-at]") {
  std::string path = fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode");
  auto f = run(tool() + " --before-layer 7 --bed 220x220 " + quote(path));
  auto s = run("cat " + quote(path) + " | " + tool() + " --before-layer 7 --bed 220x220");
  REQUIRE(f.status == 0);
  CHECK(s.status == 0);
  CHECK(s.out == f.out);
  // Prusa's bed is in its config at the end: a pipe cannot see it in time.
  auto p = run("cat " + quote(fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")) + " | " + tool() + " --before-layer 7");
  CHECK(p.status == 1);
  CHECK(p.err.find("--park") != std::string::npos);
  CHECK(p.out.empty());
}

TEST_CASE("gc-pause-at: the bed and the height limit come from the file", "[gc-pause-at]") {
  // PrusaSlicer MK3S: bed_shape 250x210, max_print_height 210.
  std::string path = fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode");
  auto r = run(tool() + " --dry-run --before-layer 5 --min-park-z 500 " + quote(path));
  INFO(r.err);
  // --min-park-z above the printer's 210 mm is refused.
  CHECK(r.status == 1);
  r = run(tool() + " --dry-run --before-layer 5 --lift 500 " + quote(path));
  REQUIRE(r.status == 0);
  std::vector<DryRow> rows = parse_dry_run(r.out);
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].park.substr(rows[0].park.find(' ')) == " Y200");
  CHECK(r.out.find("Z210\n") != std::string::npos);
  // Cura without --bed: the park position is unknown, nothing is written.
  r = run(tool() + " --before-layer 5 " + quote(fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode")));
  CHECK(r.status == 1);
  CHECK(r.err.find("--park X,Y") != std::string::npos);
  CHECK(r.out.empty());
  r = run(tool() + " --before-layer 5 --park 10,200 " + quote(fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode")));
  CHECK(r.status == 0);
  CHECK(r.out.find("\nG1 X10 Y200 F3600\n") != std::string::npos);
}

TEST_CASE("gc-pause-at: a purge over the print is refused (Cura #13317)", "[gc-pause-at]") {
  std::string path = fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode");
  auto r = run(tool() + " --before-layer 5 --park 110,110 --purge 20 " + quote(path));
  CHECK(r.status == 1);
  CHECK(r.err.find("above the print") != std::string::npos);
  // Parking over the print without pushing filament there is allowed.
  r = run(tool() + " --before-layer 5 --park 110,110 " + quote(path));
  CHECK(r.status == 0);
}

TEST_CASE("gc-pause-at: errors are clear, exit 1 or 2, and -i leaves the file alone", "[gc-pause-at]") {
  std::string dir = gctest::temp_dir();
  std::string copy = dir + "/cube.gcode";
  std::string original = read_file(fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode"));
  gctest::write_file(copy, original);
  struct Case {
    std::string args;
    int status;
    const char* message;
  };
  const std::vector<Case> cases = {
      {"--before-layer 500", 1, "no such layer, the file has 100 layers"},
      {"--after-layer 101", 1, "no such layer"},
      {"--z 500", 1, "no layer starts above"},
      {"--every 100", 1, "no pause"},
      {"--before-layer 5 -o x", 2, "excludes"},
      {"", 2, "nothing to do"},
      {"--before-layer 5 --method M0 --dwell 3", 2, "--dwell goes with --method G4"},
      {"--before-layer 5 --method M999", 2, "unknown"},
      {"--before-layer 5 --dry-run", 2, "excludes"},
      {"--before-layer -3", 2, "counted from the end"},
      {"--before-layer x", 2, ""},
      {"--before-layer 5 --retract -1", 2, ""},
      {"--before-layer 5 --park 1", 2, "X,Y"},
      {"--before-layer 5 --bed 22", 2, "WIDTHxDEPTH"},
  };
  for (const Case& c : cases) {
    auto r = run(tool() + " -i " + c.args + " " + quote(copy));
    INFO(c.args << ": " << r.err);
    CHECK(r.status == c.status);
    CHECK(r.err.find(c.message) != std::string::npos);
    CHECK(r.err.rfind("gc-pause-at: ", 0) == 0);
    CHECK(read_file(copy) == original);
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) files += entry.is_regular_file() ? 1 : 0;
    CHECK(files == 1);  // no temp file left behind
  }
  // A height above a Cura print is refused before any output.
  auto r = run(tool() + " --z 50 --bed 220x220 " + quote(fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode")));
  CHECK(r.status == 1);
  CHECK(r.err.find("only 20.4 mm high") != std::string::npos);
  CHECK(r.out.empty());
  // An empty file has no layer to pause at.
  r = run(tool() + " --before-layer 1 --bed 220x220", "");
  CHECK(r.status == 1);
  CHECK(r.err.find("no layers found") != std::string::npos);
  // -i on success rewrites the file.
  r = run(tool() + " -i --before-layer 5 " + quote(copy));
  CHECK(r.status == 0);
  CHECK(read_file(copy).find("; gc-pause-at: pause before layer 5") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("gc-pause-at: --help and the man page name the same options", "[gc-pause-at]") {
  auto r = run(tool() + " --help");
  REQUIRE(r.status == 0);
  std::string man = read_file(std::string(GC_FIXTURES_DIR) + "/../../man/gc-pause-at.1");
  std::vector<std::string> options;
  std::istringstream ss(r.out);
  for (std::string word; ss >> word;) {
    if (word.rfind("--", 0) != 0 || word.size() < 3) continue;
    std::size_t end = 2;
    while (end < word.size() && (std::isalnum(static_cast<unsigned char>(word[end])) || word[end] == '-')) ++end;
    word = word.substr(0, end);
    options.push_back(word);
  }
  CHECK(options.size() > 30);
  for (const std::string& o : options) {
    std::string roff;
    for (char ch : o) roff += ch == '-' ? std::string("\\-") : std::string(1, ch);
    INFO(o);
    CHECK(man.find(roff) != std::string::npos);
  }
}

// Issue 11: a file that never sets the E mode leaves it to the printer (a
// start macro); a pause must not switch it (an M82 in a relative-E file makes
// every later E a position, not an amount).
TEST_CASE("gc-pause-at writes no E mode into a file that never set one", "[gc-pause-at][e-mode]") {
  const std::string name = "prusa_cube_0.2_sailfish_rel_no_emode.gcode";
  std::string original = read_file(fixture_path(name));
  REQUIRE(gctest::e_mode_commands(original) == 0);
  auto r = run(tool() + " --before-layer 10 " + quote(fixture_path(name)));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(gctest::e_mode_commands(r.out) == 0);
}
