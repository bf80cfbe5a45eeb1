// A temporary driver until gc-litho's main.cpp exists (the command-line front
// end comes with the pipeline rewrite): a hidden test that writes a
// lithophane's G-code and STL from environment variables, for benchmarks
// and for looking at the output with other tools. Not run by default
// (hidden tag); run as
//   LITHO_IMAGE=pic.png LITHO_SHAPE=flat LITHO_OUT=/tmp/pic unit_tests '[litho-driver]'
// which writes /tmp/pic.gcode and /tmp/pic.stl and prints the totals.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "gcode/litho/litho_gcode.hpp"
#include "gcode/litho/stl_writer.hpp"

namespace {

std::string env(const char* name, const char* fallback) {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}

}  // namespace

TEST_CASE("litho driver writes G-code and STL from the environment", "[.][litho-driver]") {
  const std::string image_path = env("LITHO_IMAGE", "");
  if (image_path.empty()) {
    WARN("set LITHO_IMAGE (and LITHO_SHAPE=flat|cylinder, LITHO_OUT=prefix)");
    return;
  }
  const std::string out = env("LITHO_OUT", "/tmp/litho");
  gcode::litho::HeightMapOptions ho;
  if (env("LITHO_SHAPE", "flat") == "cylinder") ho.shape = gcode::litho::LithoShape::Cylinder;
  ho.width = std::stod(env("LITHO_WIDTH", "100"));
  ho.height = std::stod(env("LITHO_HEIGHT", "0"));
  ho.tone.invert = env("LITHO_INVERT", "0") == "1";
  const auto t0 = std::chrono::steady_clock::now();
  const gcode::litho::HeightMap map(gcode::litho::load_image(image_path), ho);
  const gcode::litho::LithophanePlanner planner(map, gcode::litho::LithoOptions{});
  gcode::litho::LithoGcodeOptions go;
  go.image_name = image_path;
  std::ofstream gcode_file(out + ".gcode", std::ios::binary);
  const auto stats = gcode::litho::write_litho_gcode(
      planner, go, [&](std::string_view chunk) { gcode_file.write(chunk.data(), static_cast<std::streamsize>(chunk.size())); });
  gcode_file.close();
  const auto t1 = std::chrono::steady_clock::now();
  std::ofstream stl_file(out + ".stl", std::ios::binary);
  const auto stl = gcode::litho::write_litho_stl(
      map, {}, [&](std::string_view chunk) { stl_file.write(chunk.data(), static_cast<std::streamsize>(chunk.size())); });
  const auto t2 = std::chrono::steady_clock::now();
  std::printf("litho driver: %.1f x %.1f mm, %d layers, %.3f m filament, %llu pieces (%llu clamped fast), "
              "%.1f MB G-code in %.2f s; STL %u triangles in %.2f s\n",
              map.length(), map.height(), stats.layers, stats.filament / 1000,
              static_cast<unsigned long long>(stats.pieces), static_cast<unsigned long long>(stats.clamped_fast),
              static_cast<double>(stats.bytes) / 1e6, std::chrono::duration<double>(t1 - t0).count(), stl.triangles,
              std::chrono::duration<double>(t2 - t1).count());
}
