// The plans on the splice: gc-swap-layer's edit texts (transform/layer_edits.hpp)
// and gc-relayer's join rules (transform/relayer.hpp) on small layered files.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <string>
#include <vector>

#include "gcode/core/layer_marker.hpp"
#include "gcode/transform/layer_edits.hpp"
#include "gcode/transform/relayer.hpp"
#include "test_support.hpp"

namespace {

// A PrusaSlicer-style file with one square per layer at these heights.
std::string layered(const std::vector<double>& zs, const std::vector<double>& heights = {}) {
  std::string t = "G28\nM83\nG1 Z5 F600\n";
  double previous = 0;
  for (std::size_t i = 0; i < zs.size(); ++i) {
    double h = i < heights.size() ? heights[i] : zs[i] - previous;
    t += ";LAYER_CHANGE\n;Z:" + std::to_string(zs[i]) + "\n;HEIGHT:" + std::to_string(h) + "\n";
    t += "G1 Z" + std::to_string(zs[i]) + "\nG1 X10 Y10\nG1 X20 E1\nG1 Y20 E1\n";
    previous = zs[i];
  }
  return t + "G1 Z30\nM104 S0\n";
}

struct IndexedText {
  explicit IndexedText(const std::string& text) {
    path = gctest::temp_dir() + "/layers.gcode";
    gctest::write_file(path, text);
    fd = ::open(path.c_str(), O_RDONLY);
    REQUIRE(fd >= 0);
    index = std::make_unique<gcode::LayerIndex>(fd, "new.gcode", markers);
  }
  ~IndexedText() { ::close(fd); }
  std::string path;
  int fd = -1;
  gcode::LayerMarkers markers;
  std::unique_ptr<gcode::LayerIndex> index;
};

std::vector<double> steps(double first, double step, int n) {
  std::vector<double> z;
  for (int i = 0; i < n; ++i) z.push_back(std::round((first + step * i) * 1000) / 1000);
  return z;
}

}  // namespace

TEST_CASE("splice plans: layer picks by number and by height", "[splice][edits]") {
  gcode::LayerInfo l;
  l.index = 7;
  l.z = 1.4;
  CHECK(gcode::LayerPick::parse("5-9").contains(l, 0));
  CHECK_FALSE(gcode::LayerPick::parse("8-").contains(l, 0));
  CHECK(gcode::LayerPick::parse("-3").contains(l, 9));
  CHECK(gcode::LayerPick::parse("@1.4").contains(l, 0));
  CHECK(gcode::LayerPick::parse("@1:2").contains(l, 0));
  CHECK_FALSE(gcode::LayerPick::parse("@1.5").contains(l, 0));
  CHECK(gcode::LayerPick::parse("@1.4").by_height());
  for (const char* bad : {"", "x", "@", "@x", "@2:1", "0", "5-3"}) {
    INFO(bad);
    CHECK_THROWS_AS(gcode::LayerPick::parse(bad), std::invalid_argument);
  }
}

TEST_CASE("splice plans: repeat and file texts", "[splice][edits]") {
  CHECK(gcode::RepeatText::parse("12").times == 1);
  CHECK(gcode::RepeatText::parse("12x3").times == 3);
  CHECK(gcode::RepeatText::parse("@1.2X2").layer.by_height());
  for (const char* bad : {"5x0", "5x", "5-6", "5,7x2", "@1:2x2", "x3"}) {
    INFO(bad);
    CHECK_THROWS_AS(gcode::RepeatText::parse(bad), std::invalid_argument);
  }
  gcode::FileLayersText a = gcode::FileLayersText::parse("b.gcode");
  CHECK(a.file == "b.gcode");
  CHECK_FALSE(a.layers);
  gcode::FileLayersText b = gcode::FileLayersText::parse("dir/b.gcode:5-9");
  CHECK(b.file == "dir/b.gcode");
  CHECK(b.layers->text() == "5-9");
  CHECK(gcode::FileLayersText::parse("b.gcode:@1.2").layers->by_height());
  CHECK(gcode::FileLayersText::parse("odd:name.gcode").file == "odd:name.gcode");
}

TEST_CASE("splice plans: edits that make no sense whatever the input", "[splice][edits]") {
  auto edits = [](auto&& fill) {
    gcode::LayerEditsText e;
    fill(e);
    return e;
  };
  CHECK_NOTHROW(edits([](auto& e) { e.skip = "3"; }).validate());
  CHECK_NOTHROW(edits([](auto& e) {
                  e.skip = "3";
                  e.repeat = {"5x2"};
                  e.replace = {"7-9"};
                  e.with = {"b.gcode"};
                }).validate());
  for (auto bad : std::vector<gcode::LayerEditsText>{
           {},
           edits([](auto& e) { e.replace = {"5"}; }),
           edits([](auto& e) { e.insert_after = {"5"}; }),
           edits([](auto& e) { e.keep_z = true; e.repeat = {"2"}; }),
           edits([](auto& e) { e.skip = "3-6"; e.replace = {"5"}; e.with = {"b"}; }),
           edits([](auto& e) { e.replace = {"5-6", "6"}; e.with = {"b", "c"}; }),
           edits([](auto& e) { e.skip = "4-"; e.repeat = {"9"}; }),
           edits([](auto& e) { e.replace = {"5"}; e.with = {"b"}; e.insert_after = {"5"}; e.insert_file = {"c"}; }),
           edits([](auto& e) { e.insert_after = {"5-6"}; e.insert_file = {"c"}; }),
       }) {
    CHECK_THROWS_AS(bad.validate(), std::invalid_argument);
  }
}

TEST_CASE("splice plans: join at equal heights goes on from the next layer", "[splice][join]") {
  IndexedText n(layered(steps(0.2, 0.2, 20)));
  gcode::Join j = gcode::choose_join(*n.index, 2.0, 3);
  CHECK(j.first == 11);
  CHECK(j.covered.empty());
  CHECK(j.fills.empty());
  CHECK(j.first_scale == 1);
}

TEST_CASE("splice plans: join onto thinner layers takes the first one above", "[splice][join]") {
  IndexedText n(layered(steps(0.2, 0.1, 40)));
  gcode::Join j = gcode::choose_join(*n.index, 2.0, 3);
  CHECK(n.index->layer(j.first).info.z == Approx(2.1));
  CHECK(j.fills.empty());
}

TEST_CASE("splice plans: an overlapping layer is left out and the gap under the next one filled", "[splice][join]") {
  IndexedText n(layered(steps(0.2, 0.2, 20)));
  gcode::Join j = gcode::choose_join(*n.index, 2.1, 3);
  REQUIRE(j.covered.size() == 1);
  CHECK(n.index->layer(j.covered[0]).info.z == Approx(2.2));
  CHECK(n.index->layer(j.first).info.z == Approx(2.4));
  REQUIRE(j.fills.size() == 1);
  CHECK(j.fills[0].layer == j.first);
  CHECK(j.fills[0].z_shift == gcode::Fixed::from_decimal(-2, 1));  // printed at 2.2
  CHECK(j.fills[0].scale == Approx(0.5));                          // 0.1 of its 0.2 mm
}

TEST_CASE("splice plans: a missing height of several layers is filled in steps no thicker than a layer",
          "[splice][join]") {
  // Layers at 0.2 .. 1.0, then the file goes on at 1.8 (0.2 high): 0.6 mm missing over 1.0.
  std::vector<double> z = steps(0.2, 0.2, 5);
  z.push_back(1.8);
  z.push_back(2.0);
  IndexedText n(layered(z, {0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2}));
  gcode::Join j = gcode::choose_join(*n.index, 1.0, 3);
  CHECK(j.first == 6);
  REQUIRE(j.fills.size() == 3);
  double below = 1.0;
  for (const gcode::JoinStep& s : j.fills) {
    double at = 1.8 + s.z_shift.to_double();
    CHECK(at - below == Approx(0.2));
    CHECK(s.scale == Approx(1));
    below = at;
  }
}

TEST_CASE("splice plans: within the tolerance a layer fits, beyond the file is an error", "[splice][join]") {
  IndexedText n(layered({0.2, 0.4, 0.605, 0.8}, {0.2, 0.2, 0.2, 0.2}));
  gcode::Join j = gcode::choose_join(*n.index, 0.4, 3);
  CHECK(j.first == 3);
  CHECK(j.fills.empty());
  CHECK_THROWS_AS(gcode::choose_join(*n.index, 0.8, 3), std::runtime_error);
  gcode::Candidates c = gcode::layer_candidates(*n.index, 0.5);
  CHECK(c.below == 2);
  CHECK(c.above == 3);
  CHECK(gcode::layer_candidates(*n.index, 0.1).below == 0);
  CHECK(gcode::layer_candidates(*n.index, 0.9).above == 0);
}
