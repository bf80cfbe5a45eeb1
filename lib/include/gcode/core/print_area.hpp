#pragma once
// What a G-code file says about the printer it was sliced for: the bed, the
// height limit, and the extent of the print, from the comments slicers write.
//
//   PrusaSlicer / Slic3r / SuperSlicer   ; bed_shape = 0x0,250x0,250x210,0x210
//   (config block at the END of file)    ; max_print_height = 210
//   OrcaSlicer / Bambu                   ; printable_area = 0x0,256x0,256x256,0x256
//                                        ; printable_height = 250
//   CuraEngine header (the print's box)  ;MINX:94 ;MINY:94 ;MAXX:126 ;MAXY:126 ;MAXZ:20.4
//   Cura front end machine settings      ;SETTING_3 {... machine_width = 220\\n
//                                        machine_depth = 220\\n machine_height = 250 ...}
//   Ultimaker Griffin header             ;PRINT.SIZE.MIN.X:94 ... ;PRINT.SIZE.MAX.Z:20.4
//
// and about the material and the firmware, for tools that compute flow or
// choose between firmware commands:
//
//   PrusaSlicer / Slic3r / Orca          ; filament_diameter = 1.75   (first of a list)
//                                        ; gcode_flavor = marlin2
//   Cura front end machine settings      ;SETTING_3 {... material_diameter = 2.85 ...}
//   CuraEngine header                    ;FLAVOR:Marlin
//   Simplify3D                           ;   filamentDiameters,1.75|1.75
//   Cura 15 / Craftware / IdeaMaker      ;Filament Diameter: 2.85   ;Filament diameter: 1.75mm
//                                        ;Filament Diameter #0: 1.75
//
// PrusaSlicer, SuperSlicer and OrcaSlicer also hand every setting to a
// post-processing script as an environment variable SLIC3R_<KEY> with the
// value as the config block writes it (SLIC3R_BED_SHAPE=0x0,250x0,250x210,0x210,
// SLIC3R_FILAMENT_DIAMETER=1.75); a tool run as such a script reads them
// first (slicer_environment), the file second, and its own options override
// both. The slicer's retraction (SLIC3R_RETRACT_LENGTH=0.8,0.8, the first
// extruder's) is taken from there only, for tools that retract on their own.
//
// Prusa puts its config after the G-code, so a tool that needs the bed before
// the first pause reads a regular file's head and tail first (scan_file), and
// on a pipe only what it has seen (the header, for Cura).
#include <string>

#include "gcode/core/geometry.hpp"
#include <string_view>

namespace gcode {

struct PrintArea {
  bool has_bed = false;
  Box2 bed;               // the printable area in file coordinates
  bool has_max_z = false;
  double max_z = 0;       // the printer's height limit
  bool has_print_box = false;
  Box2 print_box;         // the print's XY extent, when the slicer wrote it
  bool has_print_top = false;
  double print_top = 0;   // the print's highest Z, when the slicer wrote it
  bool has_filament_diameter = false;
  double filament_diameter = 0;  // mm (the first extruder's)
  bool has_retract_length = false;
  double retract_length = 0;     // mm (the first extruder's; from SLIC3R_RETRACT_LENGTH only)
  std::string flavor;     // the slicer's firmware flavour as written ("marlin2", "Marlin", "klipper"); "" unknown

  // Fills what `other` knows and this does not.
  void merge(const PrintArea& other);
};

class PrintAreaScanner {
 public:
  // Looks at one line (anything; only comments are read).
  void observe(std::string_view line_text);
  // Everything seen so far.
  PrintArea limits() const;

 private:
  void observe_comment(std::string_view c);

  PrintArea found_;
  double cura_box_[6] = {};
  unsigned cura_seen_ = 0;  // bit per MINX..MAXZ
  std::string cura_settings_;  // ;SETTING_3 payloads, joined
};

// The printer facts in SLIC3R_* environment variables (nothing when the
// tool is not run by one of those slicers). `lookup` reads a variable
// (std::getenv; tests pass their own).
using EnvironmentLookup = const char* (*)(const char*);
PrintArea slicer_environment(EnvironmentLookup lookup = nullptr);

// What the slicer's environment and then a regular file's head and tail say
// (on a pipe only the environment; Filter::print_area also reads a pipe's
// header).
PrintArea printer_facts(int fd, EnvironmentLookup lookup = nullptr);

// "220x220" (or "220X220"): a bed of that width and depth from 0,0.
// Returns false when the text is not two sizes above 0.
bool parse_bed_size(std::string_view text, Box2& bed);

// Reads the first and last part of a regular file (pread, the file offset is
// left alone) and scans them. Returns false when `fd` is not a regular file.
bool scan_file_limits(int fd, PrintArea& limits);

// Scans an in-memory text (a header held back from a pipe, tests).
PrintArea scan_text_limits(std::string_view text);

}  // namespace gcode
