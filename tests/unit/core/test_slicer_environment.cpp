// print_area.hpp: the printer facts a PrusaSlicer / SuperSlicer / OrcaSlicer
// post-processing hook finds in its SLIC3R_* environment, and their order
// against the file's own comments.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <map>
#include <string>

#include "gcode/core/print_area.hpp"
#include "test_support.hpp"

using namespace gcode;

namespace {

// The environment a lookup sees (a plain function: the library takes a
// function pointer, as std::getenv is).
std::map<std::string, std::string> g_env;

const char* lookup(const char* name) {
  auto it = g_env.find(name);
  return it == g_env.end() ? nullptr : it->second.c_str();
}

PrintArea facts_of_fixture(const std::string& name) {
  gctest::OpenedFile file(gctest::fixture_path(name));
  PrintArea area = printer_facts(file.fd(), lookup);
  CHECK(::lseek(file.fd(), 0, SEEK_CUR) == 0);  // read with pread: the offset stays
  return area;
}

}  // namespace

TEST_CASE("slicer environment: PrusaSlicer's values as its config writes them", "[limits][environment]") {
  // What PrusaSlicer 2.5 exports for an MK3S with two extruders.
  g_env = {{"SLIC3R_BED_SHAPE", "0x0,250x0,250x210,0x210"},
           {"SLIC3R_MAX_PRINT_HEIGHT", "210"},
           {"SLIC3R_FILAMENT_DIAMETER", "2.85,1.75"},
           {"SLIC3R_RETRACT_LENGTH", "0.8,1.2"},
           {"SLIC3R_GCODE_FLAVOR", "marlin2"},
           {"SLIC3R_LAYER_HEIGHT", "0.2"},
           {"SLIC3R_PP_OUTPUT_NAME", "/home/me/part.gcode"}};
  PrintArea a = slicer_environment(lookup);
  REQUIRE(a.has_bed);
  CHECK(a.bed.min_x == 0);
  CHECK(a.bed.max_x == 250);
  CHECK(a.bed.max_y == 210);
  REQUIRE(a.has_max_z);
  CHECK(a.max_z == 210);
  REQUIRE(a.has_filament_diameter);
  CHECK(a.filament_diameter == 2.85);  // the first extruder's
  REQUIRE(a.has_retract_length);
  CHECK(a.retract_length == 0.8);
  CHECK(a.flavor == "marlin2");
  CHECK_FALSE(a.has_print_box);  // the environment says nothing of the print itself
}

TEST_CASE("slicer environment: OrcaSlicer's names, a bed off the origin", "[limits][environment]") {
  g_env = {{"SLIC3R_PRINTABLE_AREA", "-5x-5,230x-5,230x230,-5x230"}, {"SLIC3R_PRINTABLE_HEIGHT", "250"}};
  PrintArea a = slicer_environment(lookup);
  REQUIRE(a.has_bed);
  CHECK(a.bed.min_x == -5);
  CHECK(a.bed.max_y == 230);
  CHECK(a.max_z == 250);
  CHECK_FALSE(a.has_retract_length);
}

TEST_CASE("slicer environment: nothing, empty or nonsense values are no facts", "[limits][environment]") {
  g_env = {};
  PrintArea none = slicer_environment(lookup);
  CHECK_FALSE(none.has_bed);
  CHECK_FALSE(none.has_max_z);
  CHECK_FALSE(none.has_filament_diameter);
  CHECK_FALSE(none.has_retract_length);
  CHECK(none.flavor.empty());
  g_env = {{"SLIC3R_BED_SHAPE", ""},
           {"SLIC3R_MAX_PRINT_HEIGHT", "tall"},
           {"SLIC3R_FILAMENT_DIAMETER", "175"},  // not a diameter
           {"SLIC3R_RETRACT_LENGTH", "-1"}};
  PrintArea junk = slicer_environment(lookup);
  CHECK_FALSE(junk.has_bed);
  CHECK_FALSE(junk.has_max_z);
  CHECK_FALSE(junk.has_filament_diameter);
  CHECK_FALSE(junk.has_retract_length);
  // A value never carries on into another "line".
  g_env = {{"SLIC3R_BED_SHAPE", "0x0,200x0,200x200,0x200\n; max_print_height = 99"}};
  PrintArea one = slicer_environment(lookup);
  CHECK(one.bed.max_x == 200);
  CHECK_FALSE(one.has_max_z);
}

TEST_CASE("slicer environment: it comes before the file's comments, which fill the rest", "[limits][environment]") {
  // The file says bed 250x210, filament 1.75 (its config block); its
  // "; retract_length = 0.8" is no fact here: only the hook's environment
  // changes a tool's own retraction.
  g_env = {};
  PrintArea file = facts_of_fixture("prusa_cube_0.2_mk3s_rel_zhop.gcode");
  CHECK(file.bed.max_x == 250);
  CHECK_FALSE(file.has_retract_length);
  g_env = {{"SLIC3R_BED_SHAPE", "0x0,300x0,300x300,0x300"}, {"SLIC3R_RETRACT_LENGTH", "1.5"}};
  PrintArea both = facts_of_fixture("prusa_cube_0.2_mk3s_rel_zhop.gcode");
  CHECK(both.bed.max_x == 300);
  CHECK(both.retract_length == 1.5);
  CHECK(both.max_z == 210);               // from the file
  CHECK(both.filament_diameter == 1.75);  // from the file
  // A Cura file says nothing of the bed: the environment alone gives it.
  g_env = {{"SLIC3R_BED_SHAPE", "0x0,220x0,220x220,0x220"}};
  PrintArea cura = facts_of_fixture("cura_cube_0.2_abs_zhop_skirt.gcode");
  REQUIRE(cura.has_bed);
  CHECK(cura.bed.max_y == 220);
  CHECK(cura.has_print_box);  // the file's own header still counts
}
