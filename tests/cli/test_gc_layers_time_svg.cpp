// gc-layers --time against the slicers' own estimates, and --svg / --svg-sheet
// pictures checked by an XML parser (xmllint) and a renderer (rsvg-convert).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <regex>

#include "slicer_time.hpp"
#include "test_support.hpp"

using gctest::fixture_path;
using gctest::quote;
using gctest::read_file;
using gctest::run;
using Json = nlohmann::json;

namespace {


// Width and height from a PNG's IHDR chunk (big-endian at bytes 16..23).
std::pair<int, int> png_size(const std::string& png) {
  REQUIRE(png.size() > 24);
  REQUIRE(png.substr(1, 3) == "PNG");
  auto be = [&](std::size_t at) {
    return (static_cast<unsigned char>(png[at]) << 24) | (static_cast<unsigned char>(png[at + 1]) << 16) |
           (static_cast<unsigned char>(png[at + 2]) << 8) | static_cast<unsigned char>(png[at + 3]);
  };
  return {static_cast<int>(be(16)), static_cast<int>(be(20))};
}

// The width and height attributes of the root <svg>.
std::pair<int, int> svg_size(const std::string& svg) {
  std::smatch m;
  REQUIRE(std::regex_search(svg, m, std::regex("<svg xmlns[^>]* width=\"([0-9]+)\" height=\"([0-9]+)\"")));
  return {std::stoi(m[1]), std::stoi(m[2])};
}

// Valid XML, and rendered to a PNG of the size the SVG declares with
// something drawn (a blank white PNG of that size compresses to well under 2 kB).
void check_picture(const std::string& svg_path) {
  auto lint = run("xmllint --noout " + quote(svg_path));
  INFO(lint.err);
  REQUIRE(lint.status == 0);
  std::string png_path = svg_path + ".png";
  auto render = run("rsvg-convert " + quote(svg_path) + " -o " + quote(png_path));
  INFO(render.err);
  REQUIRE(render.status == 0);
  std::string svg = read_file(svg_path), png = read_file(png_path);
  CHECK(png_size(png) == svg_size(svg));
  CHECK(png.size() > 5000);
}

}  // namespace

TEST_CASE("gc-layers --time is within 5 % of PrusaSlicer and 10 % of Cura", "[gc-layers][time]") {
  int compared = 0;
  std::string no_firmware_retraction = gctest::temp_dir() + "/no-fw-retraction.ini";
  gctest::write_file(no_firmware_retraction, "fw_retract_length = 0\nfw_unretract_extra = 0\n");
  for (const std::string& name : gctest::fixture_names()) {
    std::string path = fixture_path(name);
    gctest::SlicerTime slicer = gctest::slicer_time(read_file(path));
    if (!slicer.found) continue;
    // Slicers leave heating out. Cura's ;TIME: assumes CuraEngine's machine
    // defaults (the "cura" profile); PrusaSlicer's limits are in the file.
    std::string profile = slicer.cura ? "--profile cura " : "";
    if (read_file(path).find("; use_firmware_retraction = 1") != std::string::npos) {
      // PrusaSlicer times G10/G11 as nothing (man gc-layers, --time): compare the rest.
      profile = "--profile " + quote(no_firmware_retraction) + " ";
    }
    auto r = run(gctest::tool_command("gc-layers", "--time --json --no-heat-time " + profile + quote(path)));
    REQUIRE(r.status == 0);
    Json j = Json::parse(r.out);
    double ours = j["summary"]["time_s"].get<double>();
    double error = (ours - slicer.seconds) / slicer.seconds;
    std::printf("time  %-42s slicer %6.0f s  ours %7.1f s  error %+5.2f %%\n", name.c_str(), slicer.seconds, ours,
                error * 100);
    INFO(name << ": slicer " << slicer.seconds << " ours " << ours);
    CHECK(std::fabs(error) < (slicer.cura ? 0.10 : 0.05));
    // The per-layer times add up to the total, and cumulative ends there
    // (each figure is rounded to the millisecond).
    double slack = 0.001 * static_cast<double>(j["layers"].size() + 2);
    double sum = j["start_code"]["time_s"].get<double>();
    for (const Json& l : j["layers"]) sum += l["time_s"].get<double>();
    CHECK(j["layers"].back()["cumulative_s"].get<double>() == Approx(sum).margin(slack));
    if (!j["end_code"].is_null()) sum += j["end_code"]["time_s"].get<double>();
    CHECK(sum == Approx(ours).margin(slack));
    ++compared;
  }
  CHECK(compared == 9);  // 3 Cura + 6 PrusaSlicer fixtures carry an estimate
}

TEST_CASE("gc-layers --time text table has time columns and a total", "[gc-layers][time]") {
  std::string path = fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode");
  auto r = run(gctest::tool_command("gc-layers", "--time " + quote(path)));
  REQUIRE(r.status == 0);
  CHECK(r.out.find("    time    cumul. features") != std::string::npos);
  CHECK(std::regex_search(r.out, std::regex("\n     1 .* 0:0[0-9]:[0-5][0-9]   0:0[0-9]:[0-5][0-9] Skirt")));
  std::smatch m;
  REQUIRE(std::regex_search(r.out, m, std::regex("print time: ([0-9]+):([0-9]{2}):([0-9]{2})")));
  // With heating counted (M190 S60, M109 S215 from 25 degrees) the total is longer than without.
  auto cold = run(gctest::tool_command("gc-layers", "--time --no-heat-time " + quote(path)));
  std::smatch m2;
  REQUIRE(std::regex_search(cold.out, m2, std::regex("print time: ([0-9]+):([0-9]{2}):([0-9]{2})")));
  auto secs = [](const std::smatch& s) { return std::stoi(s[1]) * 3600 + std::stoi(s[2]) * 60 + std::stoi(s[3]); };
  CHECK(secs(m) > secs(m2) + 60);
  // Without --time the table is unchanged.
  auto plain = run(gctest::tool_command("gc-layers", quote(path)));
  CHECK(plain.out.find("cumul.") == std::string::npos);
  // -v tells which limits were used: the file's own M201/M203.
  auto verbose = run(gctest::tool_command("gc-layers", "--time -v " + quote(path)));
  CHECK(verbose.err.find("max feed rate X200 Y200 Z12 E120") != std::string::npos);
}

TEST_CASE("gc-layers --svg draws a layer that renders, for Prusa and Cura files", "[gc-layers][svg]") {
  std::string dir = gctest::temp_dir();
  struct Case {
    const char* file;
    int layer;
    const char* feature;
  } cases[] = {{"prusa_tshape_0.2_support_mk3s_brim.gcode", 40, "Internal infill"},
               {"cura_cube_0.2_abs_zhop_skirt.gcode", 12, "WALL-OUTER"}};
  for (const Case& c : cases) {
    std::string out = dir + "/layer.svg";
    auto r = run(gctest::tool_command("gc-layers", "--svg " + std::to_string(c.layer) + " --svg-out " + quote(out) + " " +
                            quote(fixture_path(c.file))));
    INFO(c.file << ": " << r.err);
    REQUIRE(r.status == 0);
    check_picture(out);
    std::string svg = read_file(out);
    CHECK(svg.find("Layer " + std::to_string(c.layer) + " ") != std::string::npos);
    CHECK(svg.find(c.feature) != std::string::npos);        // in the legend
    CHECK(svg.find("stroke-dasharray") != std::string::npos);  // travel
    CHECK(svg.find("<circle") != std::string::npos);          // retractions
    CHECK(svg.find("#d2d2d2") != std::string::npos);          // the layer below
    CHECK(svg.size() < 200000);                               // merged polylines keep it small
    // Without travel: no dashed lines.
    auto nt = run(gctest::tool_command("gc-layers", "--svg " + std::to_string(c.layer) + " --no-travel " + quote(fixture_path(c.file))));
    REQUIRE(nt.status == 0);
    CHECK(nt.out.find("stroke-dasharray=\"") == std::string::npos);
  }
  // PrusaSlicer's bed_shape gives the bed outline.
  auto bed = run(gctest::tool_command("gc-layers", "--svg 3 " + quote(fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode"))));
  REQUIRE(bed.status == 0);
  CHECK(bed.out.find("<polygon fill=\"#f6f6f2\"") != std::string::npos);
}

TEST_CASE("gc-layers --svg with a pattern writes one file per layer, --svg-sheet one grid", "[gc-layers][svg]") {
  std::string dir = gctest::temp_dir();
  std::string path = fixture_path("cura_pegs_0.2_rel_fwretract.gcode");
  auto r = run(gctest::tool_command("gc-layers", "--svg 2-4 --svg-out " + quote(dir + "/l-{}.svg") + " " + quote(path)));
  REQUIRE(r.status == 0);
  for (int l = 2; l <= 4; ++l) CHECK(read_file(dir + "/l-" + std::to_string(l) + ".svg").find("Layer " + std::to_string(l)) != std::string::npos);
  auto s = run(gctest::tool_command("gc-layers", "--svg-sheet 1,10,50,100 --svg-out " + quote(dir + "/sheet.svg") + " " + quote(path)));
  REQUIRE(s.status == 0);
  check_picture(dir + "/sheet.svg");
  std::string sheet = read_file(dir + "/sheet.svg");
  for (const char* t : {"Layer 1 ", "Layer 10 ", "Layer 50 ", "Layer 100 "}) CHECK(sheet.find(t) != std::string::npos);
}

TEST_CASE("gc-layers --svg errors", "[gc-layers][svg]") {
  std::string path = quote(fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode"));
  auto missing = run(gctest::tool_command("gc-layers", "--svg 500 " + path));
  CHECK(missing.status == 1);
  CHECK(missing.err.find("layer 500 does not exist") != std::string::npos);
  auto several = run(gctest::tool_command("gc-layers", "--svg 1-3 " + path));
  CHECK(several.status == 1);
  CHECK(several.err.find("pattern") != std::string::npos);
  CHECK(run(gctest::tool_command("gc-layers", "--svg 1 --extract 2 " + path)).status == 2);
  CHECK(run(gctest::tool_command("gc-layers", "--svg x " + path)).status == 2);
  CHECK(run(gctest::tool_command("gc-layers", "--svg-out a.svg " + path)).status == 2);
  auto profile = run(gctest::tool_command("gc-layers", "--time --profile /nonexistent.ini " + path));
  CHECK(profile.status == 1);
  CHECK(profile.err.find("gc-layers: /nonexistent.ini") == 0);
}
