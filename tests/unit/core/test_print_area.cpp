// printer_limits.hpp: the bed, the height limit and the print's extent, from
// the comments real slicers write.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <unistd.h>

#include "gcode/core/print_area.hpp"
#include "test_support.hpp"

using namespace gcode;

namespace {

PrintArea from_fixture(const std::string& name) {
  int fd = ::open(gctest::fixture_path(name).c_str(), O_RDONLY);
  REQUIRE(fd >= 0);
  PrintArea l;
  bool ok = scan_file_limits(fd, l);
  // The scan reads with pread: the file offset stays at the start.
  CHECK(::lseek(fd, 0, SEEK_CUR) == 0);
  ::close(fd);
  REQUIRE(ok);
  return l;
}

}  // namespace

TEST_CASE("limits: PrusaSlicer's config block at the end of the file", "[limits]") {
  PrintArea l = from_fixture("prusa_cube_0.2_mk3s_rel_zhop.gcode");
  REQUIRE(l.has_bed);
  CHECK(l.bed.min_x == 0);
  CHECK(l.bed.max_x == 250);
  CHECK(l.bed.max_y == 210);
  REQUIRE(l.has_max_z);
  CHECK(l.max_z == 210);
  CHECK_FALSE(l.has_print_box);
  // Larger than head + tail: the Klipper pegs file (1.7 MB).
  PrintArea k = from_fixture("prusa_pegs_0.2_klipper_zhop_labels.gcode");
  CHECK(k.has_bed);
  CHECK(k.bed.max_y == 235);
  CHECK(k.max_z == 250);
}

TEST_CASE("limits: Slic3r's bed_shape, no height", "[limits]") {
  PrintArea l = from_fixture("slic3r_cube_0.2_abs_reprap_skirt.gcode");
  REQUIRE(l.has_bed);
  CHECK(l.bed.max_x == 220);
  CHECK(l.bed.max_y == 220);
  CHECK_FALSE(l.has_max_z);
}

TEST_CASE("limits: Cura's header is the print's box, not the bed", "[limits]") {
  PrintArea l = from_fixture("cura_cube_0.2_abs_zhop_skirt.gcode");
  CHECK_FALSE(l.has_bed);
  REQUIRE(l.has_print_box);
  CHECK(l.print_box.min_x == 94);
  CHECK(l.print_box.max_y == 126);
  REQUIRE(l.has_print_top);
  CHECK(l.print_top == 20.4);
}

TEST_CASE("limits: Cura's unset placeholders are ignored", "[limits]") {
  PrintArea l = scan_text_limits(
      ";FLAVOR:Marlin\n;MINX:2.14748e+06\n;MINY:2.14748e+06\n;MINZ:2.14748e+06\n;MAXX:-2.14748e+06\n"
      ";MAXY:-2.14748e+06\n;MAXZ:-2.14748e+06\nG28\n");
  CHECK_FALSE(l.has_print_box);
  CHECK_FALSE(l.has_print_top);
}

TEST_CASE("limits: Cura machine settings, Orca, Griffin, a centred bed", "[limits]") {
  PrintArea cura = scan_text_limits(
      ";SETTING_3 {\"global_quality\": \"[general]\\\\nversion = 4\\\\n[values]\\\\nmachine_wi\n"
      ";SETTING_3 dth = 235\\\\nmachine_depth = 240\\\\nmachine_height = 250\\\\n\"}\n");
  REQUIRE(cura.has_bed);
  CHECK(cura.bed.max_x == 235);
  CHECK(cura.bed.max_y == 240);
  CHECK(cura.max_z == 250);
  PrintArea centred = scan_text_limits(
      ";SETTING_3 machine_width = 200\\\\nmachine_depth = 100\\\\nmachine_center_is_zero = True\\\\n\n");
  CHECK(centred.bed.min_x == -100);
  CHECK(centred.bed.max_y == 50);
  PrintArea orca = scan_text_limits("; printable_area = 0x0,256x0,256x256,0x256\n; printable_height = 250\n");
  CHECK(orca.bed.max_x == 256);
  CHECK(orca.max_z == 250);
  PrintArea griffin = scan_text_limits(
      ";PRINT.SIZE.MIN.X:10\n;PRINT.SIZE.MIN.Y:20\n;PRINT.SIZE.MIN.Z:0.27\n;PRINT.SIZE.MAX.X:30\n"
      ";PRINT.SIZE.MAX.Y:40\n;PRINT.SIZE.MAX.Z:5.2\n");
  CHECK(griffin.has_print_box);
  CHECK(griffin.print_box.max_x == 30);
  CHECK(griffin.print_top == 5.2);
  // A bed polygon that does not parse is no bed; other keys are not the bed.
  CHECK_FALSE(scan_text_limits("; bed_shape = 0x0,abc\n").has_bed);
  CHECK_FALSE(scan_text_limits("; end_gcode = G1 Z{max_print_height}\n").has_max_z);
  CHECK_FALSE(scan_text_limits("G1 X10 ; bed_shapes = 0x0,1x0,1x1\n").has_bed);
}

TEST_CASE("limits: merge keeps what is known and fills the rest", "[limits]") {
  PrintArea a = scan_text_limits("; max_print_height = 200\n");
  PrintArea b = scan_text_limits("; bed_shape = 0x0,100x0,100x100,0x100\n; max_print_height = 300\n");
  a.merge(b);
  CHECK(a.max_z == 200);
  CHECK(a.has_bed);
  CHECK(a.bed.max_x == 100);
}

TEST_CASE("limits: a pipe is not a file to read ahead", "[limits]") {
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  PrintArea l;
  CHECK_FALSE(scan_file_limits(fds[0], l));
  ::close(fds[0]);
  ::close(fds[1]);
}

TEST_CASE("limits: filament diameter and firmware flavour from every slicer's comments", "[limits]") {
  // PrusaSlicer writes both in its config block at the end of the file.
  PrintArea prusa = from_fixture("prusa_cube_0.2_mk3s_rel_zhop.gcode");
  REQUIRE(prusa.has_filament_diameter);
  CHECK(prusa.filament_diameter == 1.75);
  CHECK(prusa.flavor == "marlin2");
  CHECK(from_fixture("prusa_pegs_0.2_klipper_zhop_labels.gcode").filament_diameter == 1.75);
  // CuraEngine: the flavour in the header, no diameter unless the front end wrote its settings.
  PrintArea cura = from_fixture("cura_cube_0.2_abs_zhop_skirt.gcode");
  CHECK_FALSE(cura.has_filament_diameter);
  CHECK(cura.flavor == "Marlin");
  CHECK(scan_text_limits(";SETTING_3 {\"extruder_quality\": [\"[values]\\\\nmaterial_diameter = 2.85\\\\n\"]}\n")
            .filament_diameter == 2.85);
  // A list (one per extruder) gives the first; Simplify3D, Cura 15 and IdeaMaker spellings.
  CHECK(scan_text_limits("; filament_diameter = 2.85,1.75\n").filament_diameter == 2.85);
  CHECK(scan_text_limits(";   filamentDiameters,1.75|2.85\n").filament_diameter == 1.75);
  CHECK(scan_text_limits(";Filament Diameter: 2.85\n").filament_diameter == 2.85);
  CHECK(scan_text_limits(";Filament diameter: 1.75mm\n").filament_diameter == 1.75);
  CHECK(scan_text_limits(";Filament Diameter #0: 1.75\n").filament_diameter == 1.75);
  // The first value counts; a number that is no filament is not a diameter.
  CHECK(scan_text_limits("; filament_diameter = 1.75\n; filament_diameter = 2.85\n").filament_diameter == 1.75);
  CHECK_FALSE(scan_text_limits("; filament_diameter = 0\n").has_filament_diameter);
  CHECK_FALSE(scan_text_limits("; filament_diameter = 175\n").has_filament_diameter);
  CHECK_FALSE(scan_text_limits("; filament_diameter_x = 1.75\n;Filament Diameters: 1.75\n").has_filament_diameter);
  CHECK(scan_text_limits("; gcode_flavor = klipper\n").flavor == "klipper");
  PrintArea merged = scan_text_limits("G28\n");
  merged.merge(prusa);
  CHECK(merged.filament_diameter == 1.75);
  CHECK(merged.flavor == "marlin2");
}
