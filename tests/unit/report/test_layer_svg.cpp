#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/report/layer_svg.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line_reader.hpp"
#include "test_support.hpp"

namespace {

std::vector<gcode::LayerDrawing> draw(const std::string& text, int layer) {
  gcode::LayerDrawer drawer([layer](int l) { return l == layer; });
  gctest::run_stages(text, {&drawer});
  return std::move(drawer.drawings());
}

const char* kTwoLayers =
    ";LAYER_CHANGE\n;Z:0.2\n;HEIGHT:0.2\nG1 Z0.2 F600\nM83\n;TYPE:Perimeter\n"
    "G1 X10 Y0 E1 F1200\nG1 X10 Y10 E1\nG1 X0 Y10 E1\n"
    ";LAYER_CHANGE\n;Z:0.4\n;HEIGHT:0.2\nG1 Z0.4\n;TYPE:External perimeter\n;WIDTH:0.45\n"
    "G1 X10 Y10 E1\nG1 X20 Y10 E1\nG1 E-0.8\nG1 X0 Y0\nG1 E0.8\n;TYPE:Perimeter\nG1 X5 Y0 E0.3\n";

}  // namespace

TEST_CASE("consecutive segments of one style become one polyline", "[layer_svg]") {
  auto d = draw(kTwoLayers, 2);
  REQUIRE(d.size() == 1);
  const gcode::LayerDrawing& l = d[0];
  CHECK(l.layer == 2);
  CHECK(l.z == Approx(0.4));
  // External perimeter (2 segments, one polyline), travel, perimeter.
  REQUIRE(l.paths.size() == 3);
  CHECK(l.paths[0].xy.size() == 6);
  CHECK(l.paths[0].width == Approx(0.45));
  CHECK(l.paths[1].travel);
  CHECK(!l.paths[2].travel);
  // The retraction is marked where it happened.
  REQUIRE(l.retractions.size() == 2);
  CHECK(l.retractions[0] == Approx(20));
  CHECK(l.retractions[1] == Approx(10));
  // The layer below: its three perimeter segments, one polyline, width from
  // volume: 1 mm of 1.75 mm filament over 10 mm at 0.2 mm height.
  REQUIRE(l.below.size() == 1);
  CHECK(l.below[0].xy.size() == 8);
  CHECK(l.below[0].width == Approx(1.2).margin(0.01));
}

TEST_CASE("layer_svg writes the title, legend, escaped names and the bed", "[layer_svg]") {
  auto d = draw(kTwoLayers, 2);
  REQUIRE(d.size() == 1);
  d[0].seconds = 75;
  gcode::SvgOptions o;
  o.feature_names = {"Perimeter", "External perimeter"};
  o.bed = {{0, 0}, {250, 0}, {250, 210}, {0, 210}};
  std::string svg = gcode::layer_svg(d[0], o);
  CHECK(svg.find("Layer 2  Z 0.400 mm (height 0.200)  0:01:15") != std::string::npos);
  CHECK(svg.find(">External perimeter</text>") != std::string::npos);
  CHECK(svg.find("<polygon fill=\"#f6f6f2\"") != std::string::npos);
  CHECK(svg.find("stroke-width=\"0.45\" points=\"0,10 10,10 20,10\"") != std::string::npos);
  o.feature_names = {"a<b", "c&d"};
  svg = gcode::layer_svg(d[0], o);
  CHECK(svg.find("a&lt;b") != std::string::npos);
  CHECK(svg.find("c&amp;d") != std::string::npos);
  std::vector<gcode::LayerDrawing> two{d[0], d[0]};
  CHECK(gcode::layer_sheet_svg(two, o).find("<svg x=") != std::string::npos);
  CHECK_THROWS(gcode::layer_sheet_svg({}, o));
}

TEST_CASE("feature colours and layer patterns", "[layer_svg]") {
  CHECK(gcode::feature_color("External perimeter") == gcode::feature_color("WALL-OUTER"));
  CHECK(gcode::feature_color("Perimeter") != gcode::feature_color("External perimeter"));
  CHECK(gcode::feature_color("Solid infill") != gcode::feature_color("Internal infill"));
  CHECK(gcode::feature_color("something new") == gcode::feature_color("SOMETHING NEW"));
  CHECK(gcode::expand_layer_pattern("l-{}.svg", 7) == "l-7.svg");
  CHECK(gcode::expand_layer_pattern("l-%d.svg", 12) == "l-12.svg");
  CHECK(gcode::expand_layer_pattern("plain.svg", 3) == "plain.svg");
  CHECK(!gcode::has_layer_placeholder("plain.svg"));
}

TEST_CASE("layer pictures: one a layer by the pattern, or one sheet, each with its layer's time", "[layer_svg]") {
  gcode::LayerDrawer drawer([](int l) { return l <= 2; });
  gctest::run_stages(kTwoLayers, {&drawer});
  std::vector<gcode::LayerDrawing>& drawings = drawer.drawings();
  REQUIRE(drawings.size() == 2);
  std::vector<std::pair<std::string, std::string>> written;
  auto keep = [&](const std::string& path, const std::string& svg) { written.emplace_back(path, svg); };
  const gcode::SvgOptions svg;
  gcode::write_layer_pictures(drawings, svg, {12.5}, false, "layer-{}.svg", keep);
  REQUIRE(written.size() == 2);
  CHECK(written[0].first == "layer-1.svg");
  CHECK(written[1].first == "layer-2.svg");
  CHECK(drawings[0].seconds == 12.5);
  CHECK(drawings[1].seconds == -1);  // no time known for layer 2
  CHECK(written[1].second == gcode::layer_svg(drawings[1], svg));
  written.clear();
  gcode::write_layer_pictures(drawings, svg, {}, true, "sheet.svg", keep);
  REQUIRE(written.size() == 1);
  CHECK(written[0].first == "sheet.svg");
  CHECK(written[0].second == gcode::layer_sheet_svg(drawings, svg));
  CHECK_THROWS_WITH(gcode::write_layer_pictures(drawings, svg, {}, false, "one.svg", keep),
                    "several layers selected: give --svg-out a pattern such as layer-{}.svg");
  std::vector<gcode::LayerDrawing> none;
  CHECK_THROWS_WITH(gcode::write_layer_pictures(none, svg, {}, false, "", keep), "no layer matches the selection");
}
