// gc-litho, the built tool: mode 1 lithophanes from generated pictures (and
// ImageMagick's wizard: and rose: where Debian's imagemagick is installed)
// checked by the replay checker of litho_check.hpp against the height map of
// the same picture; mode 2 on the corpus vase against gc-subdivide at the
// same resolution and an independent reading of the projections; bad input;
// --help against the man page.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/litho/stl_writer.hpp"
#include "litho_check.hpp"
#include "test_support.hpp"

using gcode::litho::GreyImage;
using gcode::litho::HeightMap;
using gcode::litho::HeightMapOptions;
using gcode::litho::LithoOptions;
using gcode::litho::LithophanePlanner;
using gcode::litho::LithoShape;
using gctest::quote;
using gctest::read_file;
using gctest::run;

namespace {

gctest::RunResult litho(const std::string& args, std::string_view input = {}) {
  return run(gctest::tool_command("gc-litho", args), input);
}

std::string saved(const GreyImage& image, const std::string& name) {
  const std::string path = gctest::temp_dir() + "/" + name;
  gctest::write_file(path, littest::pgm(image));
  return path;
}

// Thickness of the outer wall's far edge where the layer crosses `s`, from
// the beads (flat: along +Y from the base face at base_y; cylinder: out from
// the axis at angle s / r).
double measured_thickness(const std::vector<littest::Bead>& beads, bool closed, double s, double base_x,
                          double base_y, double radius, double cx, double cy) {
  double best = -1;
  for (const littest::Bead& b : beads) {
    if (b.role != littest::Role::Outer || b.length <= 0) continue;
    const double width = b.filament * littest::kFilamentArea / (b.length * 0.2);
    if (!closed) {
      const double x = base_x + s;
      if ((b.x0 - x) * (b.x1 - x) > 0 || std::abs(b.x1 - b.x0) < 1e-9) continue;
      const double t = (x - b.x0) / (b.x1 - b.x0);
      const double along = std::abs(b.x1 - b.x0) / b.length;
      best = std::max(best, b.y0 + t * (b.y1 - b.y0) - base_y + width / 2 / along);
    } else {
      const double a = s / radius;
      const double ux = std::cos(a), uy = std::sin(a), nx = -uy, ny = ux;
      const double across = nx * (b.x1 - b.x0) + ny * (b.y1 - b.y0);
      if (std::abs(across) < 1e-12) continue;
      const double tau = (nx * (cx - b.x0) + ny * (cy - b.y0)) / across;
      if (tau < 0 || tau > 1) continue;
      const double px = b.x0 + tau * (b.x1 - b.x0) - cx, py = b.y0 + tau * (b.y1 - b.y0) - cy;
      if (ux * px + uy * py < 0) continue;
      best = std::max(best, std::hypot(px, py) - radius + width / 2 / (std::abs(across) / b.length));
    }
  }
  return best;
}

struct Lithophane {
  std::string gcode;
  littest::Measured measured;
  int layers = 0;
};

// Runs mode 1 on a picture, replays the output and checks the invariants
// every picture meets: each layer's volume within 3 %, the extruder rate of
// unclamped passes within 1 %, the layers gc-layers finds, the types.
Lithophane prove(const std::string& name, const std::string& image, const std::string& args,
                 const HeightMapOptions& map_options, double gap_step) {
  auto r = litho(quote(image) + " " + args);
  REQUIRE(r.status == 0);
  const HeightMap map(gcode::litho::load_image(image), map_options);
  const LithophanePlanner planner(map, LithoOptions{});
  Lithophane l;
  l.gcode = r.out;
  l.measured = littest::measure(map, planner, r.out, gap_step);
  l.layers = planner.layer_count();
  const littest::Measured& m = l.measured;
  std::printf("gc-litho %-18s layers %4zu  volume error %.3f %%  widest gap %.4f mm  rate error %.3f %% over %zu pieces\n",
              name.c_str(), m.layers, m.worst_volume_error * 100, m.worst_gap, m.worst_rate_error * 100, m.rate_pieces);
  CHECK(m.layers == static_cast<std::size_t>(planner.layer_count()));
  CHECK(m.worst_volume_error < 0.03);
  CHECK(m.rate_pieces > 500);
  CHECK(m.worst_rate_error < 0.01);
  // gc-layers reads the output as a Cura file: the layers and the types.
  auto j = run(gctest::tool_command("gc-layers", "--json"), r.out);
  REQUIRE(j.status == 0);
  const nlohmann::json table = nlohmann::json::parse(j.out);
  CHECK(table["layers"].size() == static_cast<std::size_t>(planner.layer_count()));
  CHECK_THAT(r.out, Catch::Contains(";TYPE:WALL-OUTER\n") && !Catch::Contains(";TYPE:WALL-INNER\n") &&
                        Catch::Contains(";TYPE:FILL\n") && Catch::Contains(";TIME:"));
  return l;
}

HeightMapOptions flat(double width) {
  HeightMapOptions o;
  o.width = width;
  return o;
}

HeightMapOptions tube(double diameter, double height = 0) {
  HeightMapOptions o;
  o.shape = LithoShape::Cylinder;
  o.diameter = diameter;
  o.height = height;
  return o;
}

}  // namespace

TEST_CASE("gc-litho flat gradient: volume, no gaps, constant rate, thickness = the picture's mapping",
          "[gc-litho][litho]") {
  const GreyImage image = littest::gradient(64, 32);
  const std::string path = saved(image, "gradient.pgm");
  const Lithophane l = prove("flat gradient", path, "--width 40", flat(40), 0.11);
  CHECK(l.layers == 100);
  CHECK(l.measured.worst_gap <= 0.05);
  // Thickness at sampled points, from the pixels alone: darker = thicker,
  // linear between pixel centres (a plate 40 mm wide, 20 mm high, 64 x 32 pixels).
  const littest::Replayed r = littest::replay(l.gcode);
  const HeightMap map(image, flat(40));
  const LithophanePlanner planner(map, LithoOptions{});
  const auto base = planner.point_at(0, 0);
  const double pixel = 40.0 / 64;
  int sampled = 0;
  for (int layer : {10, 50, 90}) {
    std::vector<littest::Bead> beads;
    for (const auto& b : r.beads)
      if (b.layer == layer) beads.push_back(b);
    for (int column = 2; column < 62; column += 5) {
      const double s = (column + 0.5) * pixel;
      const double expected = 0.8 + (1 - image.at(column, 0) / 255.0) * (3.0 - 0.8);
      INFO("layer " << layer << " column " << column);
      CHECK(measured_thickness(beads, false, s, base.x, base.y, 0, 0, 0) == Approx(expected).margin(0.03));
      ++sampled;
    }
  }
  CHECK(sampled == 36);
  // The header's ;TIME: is what gc-layers --time estimates for the same file.
  auto timed = run(gctest::tool_command("gc-layers", "--time --json"), l.gcode);
  REQUIRE(timed.status == 0);
  const double estimated = nlohmann::json::parse(timed.out)["summary"]["time_s"].get<double>();
  const std::size_t at = l.gcode.find(";TIME:");
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(l.gcode.substr(at + 6)) == Approx(estimated).margin(1));
  // --invert: light = thick, the same mapping turned round.
  auto inverted = litho(quote(path) + " --width 40 --invert");
  REQUIRE(inverted.status == 0);
  const littest::Replayed ri = littest::replay(inverted.out);
  std::vector<littest::Bead> beads;
  for (const auto& b : ri.beads)
    if (b.layer == 50) beads.push_back(b);
  for (int column = 2; column < 62; column += 10) {
    const double expected = 0.8 + image.at(column, 0) / 255.0 * (3.0 - 0.8);
    CHECK(measured_thickness(beads, false, (column + 0.5) * pixel, base.x, base.y, 0, 0, 0) ==
          Approx(expected).margin(0.03));
  }
}

TEST_CASE("gc-litho cylinder gradient: volume, no gaps, constant rate, thickness = the picture's mapping",
          "[gc-litho][litho]") {
  const GreyImage image = littest::gradient(64, 16);
  const std::string path = saved(image, "gradient.pgm");
  const Lithophane l = prove("cylinder gradient", path, "--shape cylinder --diameter 30", tube(30), 0.23);
  CHECK(l.measured.worst_gap <= 0.05);
  const littest::Replayed r = littest::replay(l.gcode);
  const double circumference = 30 * std::numbers::pi, pixel = circumference / 64;
  for (int layer : {20, 60}) {
    std::vector<littest::Bead> beads;
    for (const auto& b : r.beads)
      if (b.layer == layer) beads.push_back(b);
    for (int column = 3; column < 62; column += 7) {
      const double s = (column + 0.5) * pixel;
      const double expected = 0.8 + (1 - image.at(column, 0) / 255.0) * (3.0 - 0.8);
      INFO("layer " << layer << " column " << column);
      CHECK(measured_thickness(beads, true, s, 0, 0, 15, 110, 110) == Approx(expected).margin(0.03));
    }
  }
}

TEST_CASE("gc-litho on text-like strokes: volume and rate hold, gaps only beside the steepest edges",
          "[gc-litho][litho]") {
  const std::string path = saved(littest::strokes(120, 60), "strokes.pgm");
  const Lithophane l = prove("flat strokes", path, "--width 40", flat(40), 0.11);
  // A bead has one width per piece; where the depth jumps 2.2 mm within a
  // pixel the planner samples the pixel's corners and cuts the pieces there
  // until neighbouring beads are at most 0.05 mm apart, as everywhere.
  CHECK(l.measured.worst_gap <= 0.05);
}

TEST_CASE("gc-litho on ImageMagick's wizard and rose, flat and cylinder", "[gc-litho][litho]") {
  if (run("test -x /usr/bin/convert").status != 0) {
    WARN("skipped: /usr/bin/convert (Debian's imagemagick) is not installed");
    return;
  }
  const std::string dir = gctest::temp_dir();
  for (const std::string name : {"rose", "wizard"}) {
    const std::string file = dir + "/" + name + ".png";
    REQUIRE(run("/usr/bin/convert " + name + ": " + quote(file)).status == 0);
    const Lithophane f = prove(name + " flat", file, "--width 50", flat(50), 0.29);
    const Lithophane c = prove(name + " cylinder", file, "--shape cylinder --diameter 20 --height 25", tube(20, 25), 0.29);
    // The rose is a photograph (soft edges); the wizard a cartoon with black
    // outlines one or two pixels wide: the same limit for both.
    CHECK(f.measured.worst_gap <= 0.05);
    CHECK(c.measured.worst_gap <= 0.05);
  }
  // Real text, drawn by ImageMagick with its own fonts (skipped where it has none).
  const std::string text = dir + "/text.png";
  if (run("/usr/bin/convert -size 300x100 xc:white -fill black -pointsize 60 -annotate +10+70 gc-litho " +
          quote(text)).status != 0) {
    WARN("skipped the text picture: ImageMagick cannot draw text here (no fonts)");
    return;
  }
  const Lithophane t = prove("text flat", text, "--width 60", flat(60), 0.17);
  // Black glyphs on white: hard edges, as the strokes and the wizard's outlines.
  CHECK(t.measured.worst_gap <= 0.05);
}

TEST_CASE("gc-litho writes the parameters, the start and end code given, and the same solid as STL", "[gc-litho]") {
  const std::string dir = gctest::temp_dir();
  const GreyImage image = littest::gradient(32, 16);
  const std::string path = saved(image, "g.pgm");
  gctest::write_file(dir + "/start.gcode", "G28 ; my start\n");
  gctest::write_file(dir + "/end.gcode", "M84 ; my end\n");
  auto r = litho(quote(path) + " --width 30 --min 1 --max 2.4 --nozzle-temp 215 --bed-temp 55 --wall-speed 30 " +
                 "--start " + quote(dir + "/start.gcode") + " --end " + quote(dir + "/end.gcode") + " --stl " +
                 quote(dir + "/g.stl") + " -o " + quote(dir + "/g.gcode"));
  REQUIRE(r.status == 0);
  CHECK(r.out.empty());
  const std::string text = read_file(dir + "/g.gcode");
  CHECK_THAT(text, Catch::Contains("min = 1 mm") && Catch::Contains("max = 2.4 mm") &&
                       Catch::Contains("wall_speed = 30 mm/s") && Catch::Contains("nozzle_temp = 215 C") &&
                       Catch::Contains("G28 ; my start\n") && Catch::EndsWith("M84 ; my end\n") &&
                       !Catch::Contains("M190"));
  HeightMapOptions ho = flat(30);
  ho.min_thickness = 1;
  ho.max_thickness = 2.4;
  const HeightMap map(image, ho);
  const std::string stl = read_file(dir + "/g.stl");
  const std::uint32_t triangles = gcode::litho::litho_stl_triangles(map, {});
  CHECK(stl.size() == 84 + 50 * static_cast<std::size_t>(triangles));
  // The same picture as PNG, JPEG, BMP and PGM (the fixtures): the same plate.
  int layers = -1;
  for (const char* format : {"png", "jpg", "bmp", "pgm"}) {
    INFO(format);
    auto f = litho(quote(std::string(GC_FIXTURES_DIR) + "/images/gradient." + format) + " --width 20");
    REQUIRE(f.status == 0);
    const int n = littest::replay(f.out).layer_markers;
    CHECK(n > 10);
    if (layers >= 0) CHECK(n == layers);
    layers = n;
  }
}

namespace {

// One extruding or travel move of a file, as MachineState replays it.
struct Step {
  double x0, y0, z0, x1, y1, z1;
  double filament, feed, length;
  bool extruding;
};

std::vector<Step> steps(std::string_view text, std::vector<std::string>* other_lines = nullptr) {
  std::vector<Step> out;
  gcode::MachineState state;
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) {
    const gcode::Line line = gcode::Line::parse(raw.text);
    const gcode::Move m = state.apply(line);
    if (m.extruding) {
      out.push_back({m.start[0], m.start[1], m.start[2], m.end[0], m.end[1], m.end[2], m.filament, m.feedrate,
                     m.length, true});
    } else if (other_lines != nullptr && line.kind != gcode::CommandKind::None) {
      other_lines->emplace_back(raw.text);
    }
  }
  return out;
}

// What the picture says at a point, read from texture.hpp's description of
// the projections (not from the library's code): the pixel's speed in mm/min.
struct Paint {
  std::string projection;
  double cx = 110, cy = 110, cz = 50, bottom = 10, w = 60, h = 80;
  double low = 20, high = 40;
  bool pixel(const GreyImage& image, double x, double y, double z, double& feed) const {
    double u = 0, v = 0;
    const double tau = 2 * std::numbers::pi;
    if (projection == "y" || projection == "x") {
      u = ((projection == "y" ? x - cx : y - cy)) / w + 0.5;
      v = 1 - (z - bottom) / h;
    } else if (projection == "z") {
      u = (x - cx) / w + 0.5;
      v = 0.5 - (y - cy) / h;
    } else {
      // Angle from the front (-Y), counter-clockwise seen from above.
      double angle = std::atan2(y - cy, x - cx) + std::numbers::pi / 2;
      u = 0.5 + angle / tau;
      u -= std::floor(u);
      v = projection == "sphere" ? 0.5 - std::atan2(z - cz, std::hypot(x - cx, y - cy)) / std::numbers::pi
                                 : 1 - (z - bottom) / h;
    }
    if (u < 0 || u > 1 || v < 0 || v > 1) return false;
    // Stay off pixel borders, where a rounding decides.
    const double px = u * image.width(), py = v * image.height();
    if (std::abs(px - std::round(px)) < 1e-3 || std::abs(py - std::round(py)) < 1e-3) return false;
    const int ix = std::min(image.width() - 1, static_cast<int>(px)), iy = std::min(image.height() - 1, static_cast<int>(py));
    // F as the file writes it: one decimal (the vase's start code has F1500.0).
    feed = std::round((low + image.at(ix, iy) / 255.0 * (high - low)) * 600) / 10;
    return true;
  }
};

// A picture of many grey levels: every pixel another speed.
GreyImage levels() {
  std::vector<std::uint8_t> px(24 * 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 24; ++x) px[static_cast<std::size_t>(y * 24 + x)] = static_cast<std::uint8_t>((x * 37 + y * 11) % 256);
  return {24, 32, std::move(px)};
}

const std::string kVase = "cura_vase_0.2_spiralize.gcode";

}  // namespace

TEST_CASE("gc-litho --texture on the vase: gc-subdivide's path, E per second kept, speeds = the picture, "
          "travel and retractions untouched",
          "[gc-litho][texture]") {
  const std::string input = read_file(gctest::fixture_path(kVase));
  const GreyImage image = levels();
  const std::string picture = saved(image, "levels.pgm");
  auto cut = run(gctest::tool_command("gc-subdivide", "--max 0.2 --no-travel"), input);
  REQUIRE(cut.status == 0);
  std::vector<std::string> cut_other, input_other;
  const std::vector<Step> reference = steps(cut.out, &cut_other);
  steps(input, &input_other);
  CHECK(cut_other == input_other);  // gc-subdivide --no-travel leaves those lines alone too
  for (const char* projection : {"cylinder", "y", "x", "z", "sphere"}) {
    INFO(projection);
    Paint paint;
    paint.projection = projection;
    std::string args = "--texture " + quote(picture) + " --projection " + projection + " --low 20 --high 40";
    if (paint.projection == "z") paint.h = paint.w * 32 / 24, args += " --width 60";
    else if (paint.projection != "sphere") args += " --height 80 --bottom 10", paint.w = paint.h * 24 / 32;
    else args += " --center 110,110,50 " + quote(gctest::fixture_path(kVase));  // FILE right after X,Y,Z
    auto r = litho(args, input);
    REQUIRE(r.status == 0);
    CHECK(r.err.empty());
    std::vector<std::string> other;
    const std::vector<Step> painted = steps(r.out, &other);
    REQUIRE(painted.size() == reference.size());
    std::size_t checked = 0, textured = 0;
    double worst_rate = 0;
    for (std::size_t i = 0; i < painted.size(); ++i) {
      const Step &a = reference[i], &b = painted[i];
      REQUIRE(a.x1 == b.x1);
      REQUIRE(a.y1 == b.y1);
      REQUIRE(a.z1 == b.z1);
      // E per second: filament / (length / speed), within 0.5 % where the
      // file's 5 decimals of E allow it (a piece of 0.002 mm of filament has
      // 0.5 % in its last digit); shorter pieces within their rounding.
      const double before = a.filament * a.feed / a.length, after = b.filament * b.feed / b.length;
      if (a.filament >= 0.004) {
        worst_rate = std::max(worst_rate, std::abs(after / before - 1));
      } else {
        REQUIRE(std::abs(b.filament - a.filament * a.feed / b.feed) <= 1.5e-5 + 0.005 * b.filament);
      }
      if (b.feed != a.feed) ++textured;
      double expected = 0;
      if (i % 7 == 0 && paint.pixel(image, (b.x0 + b.x1) / 2, (b.y0 + b.y1) / 2, (b.z0 + b.z1) / 2, expected)) {
        REQUIRE(b.feed == expected);
        ++checked;
      }
    }
    std::printf("gc-litho --texture %-8s %zu of %zu pieces at a new speed, %zu sampled against the picture, "
                "worst E/s change %.3f %%\n",
                projection, textured, painted.size(), checked, worst_rate * 100);
    CHECK(worst_rate < 0.005);
    CHECK(checked > 1000);
    // Travel, retractions and every other line: the input's, in order; the
    // tool adds its header, the G92 E that brings absolute E back in step and
    // the G1 F that puts the input's speed back after a painted run.
    std::vector<std::string> own;
    for (const std::string& line : other)
      if (line.find("; gc-litho:") == std::string::npos) own.push_back(line);
    CHECK(own == input_other);
    CHECK_THAT(r.out, Catch::Contains("; gc-litho --texture") && Catch::Contains(std::string("projection = ") + projection));
  }
}

TEST_CASE("gc-litho --texture: binary speeds, --types, --skip-z, relative E", "[gc-litho][texture]") {
  const std::string input = read_file(gctest::fixture_path(kVase));
  const std::string picture = saved(levels(), "levels.pgm");
  auto r = litho("--texture " + quote(picture) + " --height 80 --bottom 10 --binary 0.5 --high 30 --ratio 0.6 "
                 "--types WALL-OUTER --skip-z 5", input);
  REQUIRE(r.status == 0);
  std::set<double> speeds;
  for (const Step& s : steps(r.out))
    if (s.z0 > 10.05 && s.z1 < 89.95) speeds.insert(s.feed);
  CHECK(speeds == std::set<double>{1080, 1800});  // 30 x 0.6 and 30 mm/s
  // Below 5 mm (the skin and the first turns) the output is the input, line
  // for line, after the header comment.
  std::vector<std::string> in_lines = gctest::split_lines(input), out_lines;
  for (const std::string& line : gctest::split_lines(r.out))
    if (!line.starts_with("; gc-litho") && !line.starts_with(";   ")) out_lines.push_back(line);
  std::size_t low = 0;
  gcode::MachineState state;
  for (; low < in_lines.size(); ++low) {
    const std::string text = in_lines[low].substr(0, in_lines[low].find_first_of("\r\n"));
    if (state.apply(gcode::Line::parse(text)).end[2] > 4.79) break;
  }
  REQUIRE(low > 1000);
  REQUIRE(out_lines.size() > low);
  CHECK(std::equal(in_lines.begin(), in_lines.begin() + static_cast<std::ptrdiff_t>(low), out_lines.begin()));
  CHECK(litho("--texture " + quote(picture) + " --height 80 --skip-z 5 --z-range 6:", input).status == 2);
}

TEST_CASE("gc-litho --texture on a relative-E non-spiral print works, with a note", "[gc-litho][texture]") {
  const std::string input = gctest::head_of("cura_pegs_0.2_rel_fwretract.gcode", 6000);
  const std::string picture = saved(levels(), "levels.pgm");
  auto r = litho("--texture " + quote(picture) + " --height 20", input);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.err, Catch::Contains("not a spiral"));
  CHECK(r.out.find("gc-litho: E back in step") == std::string::npos);  // relative E needs no G92
  const std::vector<Step> a = steps(gctest::subdivided(input, 0.2)), b = steps(r.out);
  REQUIRE(a.size() == b.size());
  std::size_t changed = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    // E per second within 0.5 %, and within the last digit of E on tiny pieces.
    REQUIRE(std::abs(b[i].filament - a[i].filament * a[i].feed / b[i].feed) <= 1.5e-5 + 0.005 * b[i].filament);
    changed += a[i].feed != b[i].feed;
  }
  CHECK(changed > 100);
}

TEST_CASE("gc-litho --texture --types WALL-OUTER paints the outer walls only, -i replaces the file only on success",
          "[gc-litho][texture]") {
  const std::string input = read_file(gctest::fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode"));
  const std::string picture = saved(levels(), "levels.pgm");
  auto r = litho("--texture " + quote(picture) + " --projection y --width 20 --center 110,110 --types WALL-OUTER", input);
  REQUIRE(r.status == 0);
  // Every other feature's extrusions: the same moves at the same speeds.
  struct Done {
    double x, y, z, feed;
    bool operator==(const Done&) const = default;
  };
  auto others = [](const std::string& text, std::size_t& outer_changed_or_count) {
    const gctest::LinePlace places = gctest::places_of(text);
    std::vector<Done> done;
    for (const auto& m : gctest::replay_moves(text)) {
      if (!m.move.extruding) continue;
      if (places.feature[m.line_index] == "WALL-OUTER") {
        ++outer_changed_or_count;
        continue;
      }
      done.push_back({m.move.end[0], m.move.end[1], m.move.end[2], m.move.feedrate});
    }
    return done;
  };
  std::size_t outer_in = 0, outer_out = 0;
  const std::vector<Done> before = others(input, outer_in), after = others(r.out, outer_out);
  REQUIRE(before.size() > 1000);
  CHECK(after == before);
  CHECK(outer_out > outer_in);  // the outer walls were cut into pieces and painted
  // -i: a usage error leaves the file alone; a run replaces it.
  const std::string file = gctest::temp_dir() + "/cube.gcode";
  gctest::write_file(file, input);
  CHECK(litho("--texture " + quote(picture) + " -i " + quote(file)).status == 2);  // no size
  CHECK(read_file(file) == input);
  REQUIRE(litho("--texture " + quote(picture) + " --projection y --width 20 --types WALL-OUTER -i " + quote(file)).status == 0);
  CHECK(read_file(file) == r.out);
}

TEST_CASE("gc-litho: bad pictures and bad options get clear messages and the exit status", "[gc-litho][errors]") {
  const std::string dir = gctest::temp_dir();
  // The picture fixtures: an empty file, one pixel, text named .png, and a
  // PGM header that claims 20000 x 20000 pixels (400 megapixels) over a few
  // bytes: refused from the header, before anything is decoded.
  const std::string images = std::string(GC_FIXTURES_DIR) + "/images/";
  const std::string good = saved(littest::gradient(16, 8), "good.pgm");
  struct Case {
    std::string args;
    int status;
    std::string message;
  };
  const std::vector<Case> cases = {
      {quote(dir + "/missing.png"), 1, "missing.png"},
      {quote(images + "empty.png"), 1, "empty"},
      {quote(images + "one_pixel.pgm"), 1, "1 x 1"},
      {quote(images + "huge_header.pgm"), 1, "20000 x 20000"},
      {quote(images + "not_an_image.png"), 1, "not a picture"},
      {quote(good) + " --min 3 --max 3", 2, "--max"},
      {quote(good) + " --min 2 --max 1", 2, "--max"},
      {"", 2, "give the picture"},
      {quote(good) + " --shape cone", 2, "--shape"},
      {quote(good) + " --low 10", 2, "--texture"},
      {quote(good) + " --start " + quote(dir + "/none.gcode"), 1, "--start"},
      {"--texture " + quote(good) + " --stl x.stl", 2, "--stl"},
      {"--texture " + quote(good), 2, "--height"},
      {"--texture " + quote(good) + " --height 10 --low 50 --high 40", 2, "--low"},
      {"--texture " + quote(good) + " --height 10 --center 110", 2, "--center: expected X,Y or X,Y,Z"},
      {quote(good) + " --center 1,2,3", 2, "--center: expected X,Y"},
      {"--texture " + quote(good) + " --height 10 --offset 1,2,3", 2, "--offset"},
      {"--texture " + quote(images + "huge_header.pgm") + " --height 10", 1, "20000 x 20000"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    auto r = litho(c.args, "G1 X1 E1\n");
    CHECK(r.status == c.status);
    CHECK_THAT(r.err, Catch::StartsWith("gc-litho: ") && Catch::Contains(c.message));
    CHECK(r.out.empty());
  }
}

TEST_CASE("gc-litho --help names every option of the man page", "[gc-litho]") {
  auto help = litho("--help");
  REQUIRE(help.status == 0);
  const std::string man = read_file(std::string(GC_FIXTURES_DIR) + "/../../man/gc-litho.1");
  const std::set<std::string> in_help = gctest::long_options(help.out), in_man = gctest::long_options(man);
  CHECK(in_help == in_man);
  CHECK(in_help.count("--texture") == 1);
  CHECK(in_help.count("--max-pass-width") == 1);
}
