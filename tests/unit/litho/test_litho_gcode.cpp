#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "gcode/litho/litho_gcode.hpp"
#include "gcode/litho/path_order.hpp"
#include "litho_check.hpp"
#include "test_support.hpp"

using gcode::litho::GreyImage;
using gcode::litho::HeightMap;
using gcode::litho::HeightMapOptions;
using gcode::litho::LithoGcodeOptions;
using gcode::litho::LithoOptions;
using gcode::litho::LithophanePlanner;
using gcode::litho::LithoShape;
using littest::Bead;
using littest::kFilamentArea;
using littest::Measured;
using littest::plate;
using littest::measure;
using littest::Role;

namespace {

struct Generated {
  std::string text;
  gcode::litho::LithoGcodeStats stats;
  std::vector<std::size_t> chunks;
};

Generated generate(const LithophanePlanner& planner, const LithoGcodeOptions& options = {}) {
  Generated g;
  g.stats = gcode::litho::write_litho_gcode(planner, options, [&](std::string_view chunk) {
    g.text.append(chunk);
    g.chunks.push_back(chunk.size());
  });
  return g;
}

HeightMapOptions cylinder(double diameter) {
  HeightMapOptions o;
  o.shape = LithoShape::Cylinder;
  o.diameter = diameter;
  return o;
}

void report(const char* name, const Measured& m, const gcode::litho::LithoGcodeStats& stats) {
  std::printf("litho %-22s layers %4zu  volume error %.3f %%  widest gap %.4f mm  surface %.4f mm  "
              "rate error %.3f %% over %zu pieces  clamped %llu/%llu of %llu pieces\n",
              name, m.layers, m.worst_volume_error * 100, m.worst_gap, m.worst_surface, m.worst_rate_error * 100,
              m.rate_pieces, static_cast<unsigned long long>(stats.clamped_fast),
              static_cast<unsigned long long>(stats.clamped_slow), static_cast<unsigned long long>(stats.pieces));
}

// Generates the lithophane with the default options, measures it, prints
// the numbers and checks what holds for every picture: each layer's volume
// within 3 % and the extruder rate within 1 %.
Measured prove(const char* name, const HeightMap& map, double gap_step) {
  const LithophanePlanner planner(map, LithoOptions{});
  const Generated g = generate(planner);
  const Measured m = measure(map, planner, g.text, gap_step);
  report(name, m, g.stats);
  CHECK(m.layers == static_cast<std::size_t>(planner.layer_count()));
  CHECK(m.worst_volume_error < 0.03);
  CHECK(std::abs(m.total_volume / m.expected_volume - 1) < 0.001);  // the paper's: completely filled
  CHECK(m.rate_pieces > 1000);
  CHECK(m.worst_rate_error < 0.01);
  return m;
}

}  // namespace

TEST_CASE("litho G-code: flat gradient lithophane deposits each layer's band volume with no gaps at a constant rate",
          "[litho][gcode]") {
  const Measured m = prove("flat gradient", HeightMap(littest::gradient(64, 32), plate(40)), 0.11);
  CHECK(m.layers == 100);
  CHECK(m.worst_gap <= 0.05);
  CHECK(m.worst_surface <= 0.05);
}

TEST_CASE("litho G-code: cylinder gradient lithophane deposits each layer's band volume with no gaps at a constant rate",
          "[litho][gcode]") {
  const Measured m = prove("cylinder gradient", HeightMap(littest::gradient(64, 16), cylinder(30)), 0.23);
  CHECK(m.worst_gap <= 0.05);
  CHECK(m.worst_surface <= 0.05);
}

TEST_CASE("litho G-code: hard edged strokes keep the volume and the rate of unclamped pieces", "[litho][gcode]") {
  const Measured m = prove("flat strokes", HeightMap(littest::strokes(120, 60), plate(40)), 0.11);
  // On an edge the band's depth jumps 2.2 mm within one pixel (0.33 mm). A
  // bead has one width per piece, so the planner samples the pixel's corners
  // and cuts the pieces between them until no two beads are more than
  // 0.05 mm apart (0.11 mm when pieces were cut evenly to 0.05 mm per 0.2 mm
  // step, blind to the corners inside it).
  CHECK(m.worst_gap <= 0.05);
}

TEST_CASE("litho G-code: the G-code has Cura layer markers and types and every parameter in its header", "[litho][gcode]") {
  const HeightMap map(littest::gradient(64, 32), plate(40));
  const LithophanePlanner planner(map, LithoOptions{});
  LithoGcodeOptions options;
  options.image_name = "gradient.png";
  options.estimated_seconds = 1234.4;
  const Generated g = generate(planner, options);
  const auto lines = gctest::split_lines(g.text);
  CHECK(lines.front() == ";FLAVOR:Marlin\n");
  CHECK_THAT(g.text, Catch::Contains(";TIME:1234\n") && Catch::Contains(";LAYER_COUNT:100\n") &&
                         Catch::Contains(";LAYER:0\n") && Catch::Contains(";LAYER:99\n") &&
                         !Catch::Contains(";LAYER:100\n") && !Catch::Contains(";TYPE:WALL-INNER\n") &&
                         Catch::Contains(";TYPE:WALL-OUTER\n") && Catch::Contains(";TYPE:FILL\n"));
  for (const std::string& p : gcode::litho::litho_parameters(planner, options))
    CHECK_THAT(g.text, Catch::Contains(";  " + p + "\n"));
  CHECK_THAT(g.text, Catch::Contains("image = gradient.png (64 x 32 pixels)") &&
                         Catch::Contains("wall_speed = 40 mm/s") && Catch::Contains("line_width = 0.45 mm") &&
                         Catch::Contains("fill_rate = 15 mm3/s"));
  const littest::Replayed r = littest::replay(g.text);
  CHECK(r.layer_markers == 100);
  CHECK(r.layer_count_header == 100);
  for (std::size_t i = 0; i < r.layer_z.size(); ++i) REQUIRE(r.layer_z[i] == Approx(0.2 * (i + 1)));
  // Every retraction is undone before the next extrusion, so only the purge
  // line and the final retraction are filament outside the layers.
  CHECK(r.retractions > 0);
}

TEST_CASE("litho G-code: numbers are written with 4 decimals for XY 3 for Z 7 for E and whole F", "[litho][gcode]") {
  const HeightMap map(littest::gradient(16, 8), plate(20));
  const LithophanePlanner planner(map, LithoOptions{});
  const Generated g = generate(planner);
  for (const std::string& line : gctest::split_lines(g.text)) {
    if (line[0] != 'G') continue;
    const std::string text = line.substr(0, line.size() - 1);  // the Line views into it
    const gcode::Line l = gcode::Line::parse(text);
    for (const auto& w : l) {
      INFO(line);
      REQUIRE(w.raw.find_first_not_of("-0123456789.") == std::string_view::npos);
      const int limit = w.letter == 'E' ? 7 : w.letter == 'F' || w.letter == 'G' ? 0 : w.letter == 'Z' ? 3 : 4;
      REQUIRE(static_cast<int>(w.decimals) <= limit);
      if (w.decimals > 0) REQUIRE(w.raw.back() != '0');
    }
  }
}

TEST_CASE("litho G-code: each bead has its planned width and E rounding is carried", "[litho][gcode]") {
  const HeightMap map(littest::gradient(64, 32), plate(40));
  const LithophanePlanner planner(map, LithoOptions{});
  const Generated g = generate(planner);
  const littest::Replayed r = littest::replay(g.text);
  // Beads come out in the order of path_order.hpp, one per piece: E over the length
  // as written is the planned width, and the running sum of E stays within
  // the last digit of the exact running sum (rounding carried, not dropped).
  std::size_t bead = 0;
  double exact = 0, written = 0, worst_width = 0;
  gcode::litho::LithoLayer layer;
  gcode::litho::Point head;
  for (int i = 0; i < planner.layer_count(); ++i) {
    gcode::litho::plan_ordered_layer(planner, i, layer, head);
    for (const auto& path : layer.paths)
      for (const auto& piece : path.pieces) {
        REQUIRE(bead < r.beads.size());
        const Bead& b = r.beads[bead++];
        REQUIRE(b.layer == i);
        exact += piece.width * 0.2 * b.length / kFilamentArea;
        written += b.filament;
        REQUIRE(std::abs(written - exact) < 1e-5);
        worst_width = std::max(worst_width, std::abs(b.filament * kFilamentArea / (b.length * 0.2) / piece.width - 1));
      }
  }
  CHECK(bead == r.beads.size());
  CHECK(g.stats.filament == Approx(written));
  std::printf("litho widths: worst relative width error from E rounding %.4f %%\n", worst_width * 100);
}

TEST_CASE("litho G-code: output comes one layer at a time", "[litho][gcode]") {
  const HeightMap map(littest::gradient(64, 32), plate(40));
  const LithophanePlanner planner(map, LithoOptions{});
  const Generated g = generate(planner);
  // Header and start, one chunk per layer, end.
  REQUIRE(g.chunks.size() == static_cast<std::size_t>(planner.layer_count()) + 2);
  const std::size_t largest = *std::max_element(g.chunks.begin(), g.chunks.end());
  CHECK(largest < g.text.size() / 50);
  CHECK(g.stats.bytes == g.text.size());
}

TEST_CASE("litho G-code: built-in start and end code heat home purge and switch off", "[litho][gcode]") {
  const HeightMap map(littest::gradient(16, 8), plate(20));
  const LithophanePlanner planner(map, LithoOptions{});
  LithoGcodeOptions options;
  options.nozzle_temp = 215;
  options.bed_temp = 55;
  const Generated g = generate(planner, options);
  CHECK_THAT(g.text, Catch::Contains("M190 S55\n") && Catch::Contains("M109 S215\n") && Catch::Contains("G28") &&
                         Catch::Contains("M83") && Catch::Contains("; purge line") && Catch::Contains("M104 S0\n") &&
                         Catch::Contains("M140 S0\n") && Catch::Contains("M84"));
  CHECK(g.text.find("M106 S255") > g.text.find(";LAYER:1\n"));
  const gcode::MachineState end = gctest::replay_state(g.text);
  CHECK(end.relative_e);
  CHECK(end.position[gcode::kZ] > planner.layer_z(planner.layer_count() - 1) + 9);
}

TEST_CASE("litho G-code: user start and end code are used as given and the modes are set after them", "[litho][gcode]") {
  const HeightMap map(littest::gradient(16, 8), plate(20));
  const LithophanePlanner planner(map, LithoOptions{});
  LithoGcodeOptions options;
  options.start_code = "M82\nG28 ; my start";
  options.end_code = "M300 ; my end\n";
  options.start_name = "start.gcode";
  const Generated g = generate(planner, options);
  CHECK_THAT(g.text, Catch::Contains("M82\nG28 ; my start\nG90\nM83") && Catch::EndsWith("M300 ; my end\n") &&
                         !Catch::Contains("M190") && Catch::Contains("start = start.gcode"));
  options.retract_speed = 0;
  CHECK_THROWS_WITH(generate(planner, options), Catch::Contains("--retract-speed"));
}

TEST_CASE("litho G-code: ImageMagick's wizard and rose pictures print within the tolerances", "[litho][gcode]") {
  // A tool-level check with real pictures; needs Debian's imagemagick.
  if (gctest::run("test -x /usr/bin/convert").status != 0) {
    WARN("skipped: /usr/bin/convert (Debian's imagemagick) is not installed");
    return;
  }
  const std::string dir = gctest::temp_dir();
  for (const char* name : {"rose", "wizard"}) {
    const std::string file = dir + "/" + name + ".png";
    REQUIRE(gctest::run("/usr/bin/convert " + std::string(name) + ": " + gctest::quote(file)).status == 0);
    for (LithoShape shape : {LithoShape::Flat, LithoShape::Cylinder}) {
      HeightMapOptions ho = shape == LithoShape::Flat ? plate(50) : cylinder(20);
      if (shape == LithoShape::Cylinder) ho.height = 25;
      const HeightMap map(gcode::litho::load_image(file), ho);
      const Measured m = prove((std::string(name) + (shape == LithoShape::Flat ? " flat" : " cylinder")).c_str(), map, 0.29);
      // The rose is a photograph (soft edges), the wizard a cartoon with
      // black outlines (hard edges): the same limit for both.
      CHECK(m.worst_gap <= 0.05);
    }
  }
  // The wizard on a 20 mm plate: 24 pixels a mm, so its outlines climb 2.2 mm
  // within 0.04 mm, and a pass that begins on such a slope needs its own
  // piece of about a micrometre, on the written grid.
  const HeightMap small(gcode::litho::load_image(dir + "/wizard.png"), plate(20));
  const Measured m = prove("wizard 20 mm", small, 0.13);
  CHECK(m.worst_gap <= 0.05);
}
