// Every filter as a PrusaSlicer / SuperSlicer / OrcaSlicer post-processing
// script, run exactly as those slicers run one: each line of "Post-processing
// scripts" becomes `sh -c "<line> '<path>'"` with every setting exported as
// SLIC3R_<KEY>, and the file must be rewritten in place (or left alone, with
// a nonzero exit, which the slicer reports). The printer facts the tools need
// come from that environment when the file does not say, and options win.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "test_support.hpp"

namespace {

// An MK3S-like printer with a bed the Cura fixture knows nothing of.
const std::string kEnv =
    "SLIC3R_BED_SHAPE=0x0,220x0,220x220,0x220 SLIC3R_MAX_PRINT_HEIGHT=250 SLIC3R_RETRACT_LENGTH=1.5,1.5 "
    "SLIC3R_FILAMENT_DIAMETER=2.85 SLIC3R_LAYER_HEIGHT=0.2 SLIC3R_PP_OUTPUT_NAME=/home/me/cube.gcode";

// The slicer's call: `env` exported, then $SHELL -c "LINE 'PATH'".
gctest::RunResult as_slicer(const std::string& env, const std::string& line, const std::string& path) {
  return gctest::run("env " + env + " sh -c " + gctest::quote(line + " '" + path + "'"));
}

// A copy of a fixture in a directory whose name has a space, as a slicer's
// temporary file may.
std::string copy_of(const std::string& fixture) {
  std::string dir = gctest::temp_dir() + "/slicer tmp";
  std::filesystem::create_directories(dir);
  std::string path = dir + "/" + fixture;
  gctest::write_file(path, gctest::read_file(gctest::fixture_path(fixture)));
  return path;
}

// The same tool run with plain options on standard input, no environment.
std::string through(const std::string& tool, const std::string& args, const std::string& input) {
  gctest::RunResult r = gctest::run(gctest::tool_command(tool, args), input);
  INFO(tool << " " << args << ": " << r.err);
  REQUIRE(r.status == 0);
  return r.out;
}

}  // namespace

TEST_CASE("slicer hook: gc-pause-at takes the bed and the retraction from SLIC3R_*", "[slicer-hook]") {
  const std::string fixture = "cura_cube_0.2_abs_zhop_skirt.gcode";  // no bed in the file
  const std::string original = gctest::read_file(gctest::fixture_path(fixture));
  std::string path = copy_of(fixture);
  std::string line = gctest::tool_path("gc-pause-at") + " --before-layer 12 --method M600 -i";

  SECTION("without the environment the park is unknown: exit 1, the file untouched") {
    gctest::RunResult r = as_slicer("SLIC3R_PP_OUTPUT_NAME=/home/me/cube.gcode", line, path);
    CHECK(r.status == 1);
    CHECK(r.err.find("gc-pause-at: ") == 0);
    CHECK(r.err.find("bed") != std::string::npos);
    CHECK(gctest::read_file(path) == original);
  }
  SECTION("with it: rewritten in place, exactly as --bed 220x220 --max-z 250 --retract 1.5 would") {
    gctest::RunResult r = as_slicer(kEnv, line, path);
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.empty());
    std::string hooked = gctest::read_file(path);
    CHECK(hooked == through("gc-pause-at", "--before-layer 12 --method M600 --bed 220x220 --max-z 250 --retract 1.5", original));
    // The retraction is the slicer's, not the default 2 mm.
    CHECK(hooked != through("gc-pause-at", "--before-layer 12 --method M600 --bed 220x220 --max-z 250", original));
    CHECK(hooked.find("Y210") != std::string::npos);  // parked 10 mm before the far edge of 220
  }
  SECTION("options override the environment") {
    gctest::RunResult r = as_slicer(kEnv, line + " --bed 200x180 --retract 0.5", path);
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(gctest::read_file(path) ==
          through("gc-pause-at", "--before-layer 12 --method M600 --bed 200x180 --max-z 250 --retract 0.5", original));
  }
  SECTION("a request the file cannot meet: exit 1, the file untouched") {
    gctest::RunResult r = as_slicer(kEnv, gctest::tool_path("gc-pause-at") + " --before-layer 5000 -i", path);
    CHECK(r.status == 1);
    CHECK(r.err.find("gc-pause-at: ") == 0);
    CHECK(gctest::read_file(path) == original);
  }
}

TEST_CASE("slicer hook: the filament diameter from SLIC3R_FILAMENT_DIAMETER", "[slicer-hook]") {
  const std::string fixture = "cura_cube_0.2_abs_zhop_skirt.gcode";
  const std::string original = gctest::read_file(gctest::fixture_path(fixture));
  std::string path = copy_of(fixture);
  // gc-speedup's flow cap depends on the diameter: 2.85 mm filament carries
  // 2.65 times the volume per mm of 1.75.
  std::string args = "--factor 3 --max-flow 8";
  gctest::RunResult r = as_slicer(kEnv, gctest::tool_path("gc-speedup") + " " + args + " -i", path);
  INFO(r.err);
  REQUIRE(r.status == 0);
  std::string hooked = gctest::read_file(path);
  CHECK(hooked == through("gc-speedup", args + " --filament-diameter 2.85", original));
  CHECK(hooked != through("gc-speedup", args + " --filament-diameter 1.75", original));
  // gc-layers reports the mass with the slicer's diameter.
  gctest::RunResult layers =
      gctest::run("env " + kEnv + " " + gctest::tool_command("gc-layers", "--json " + gctest::quote(path)));
  REQUIRE(layers.status == 0);
  CHECK(nlohmann::json::parse(layers.out)["summary"]["filament_diameter_mm"].get<double>() == 2.85);
}

TEST_CASE("slicer hook: examples/prusaslicer/post-process.sh as the slicer runs it", "[slicer-hook]") {
  const std::string fixture = "cura_cube_0.2_abs_zhop_skirt.gcode";
  const std::string original = gctest::read_file(gctest::fixture_path(fixture));
  std::string path = copy_of(fixture);
  std::string script = std::string(GC_FIXTURES_DIR) + "/../../examples/prusaslicer/post-process.sh";
  std::string env = "PATH=" + std::string(GC_TOOLS_DIR) + ":/usr/bin:/bin " + kEnv;
  gctest::RunResult r = as_slicer(env, script, path);
  INFO(r.err);
  REQUIRE(r.status == 0);
  std::string hooked = gctest::read_file(path);
  CHECK(hooked != original);
  // Both lines of the script ran, in order, on the slicer's file.
  std::string paused = through("gc-pause-at", "--before-layer 12 --method M600 --bed 220x220 --max-z 250 --retract 1.5", original);
  CHECK(hooked == through("gc-speedup", "--factor 0.5 --layers 1-3", paused));
  // Without the bed the hook fails and the slicer keeps the file as it was.
  gctest::write_file(path, original);
  gctest::RunResult bad = as_slicer("PATH=" + std::string(GC_TOOLS_DIR) + ":/usr/bin:/bin", script, path);
  CHECK(bad.status != 0);
  CHECK(gctest::read_file(path) == original);
}
