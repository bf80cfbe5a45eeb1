#include "gcode/cli/deform_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <stdexcept>

#include "gcode/core/number.hpp"
#include "gcode/core/print_area.hpp"

namespace gcode::cli {

namespace {

void add_map_options(CLI::App& app, DeformToolOptions& o) {
  auto* xyz = app.add_option("--xyz", o.xyz, "The new X, Y and Z as formulas in x, y, z")
                  ->type_name("FX FY FZ")->expected(3)->allow_extra_args(false);
  auto* cyl = app.add_option("--cylinder", o.cylinder, "The new radius, angle (radians) and Z in r, theta, z")
                  ->type_name("FR FTHETA FZ")->expected(3)->allow_extra_args(false);
  xyz->excludes(cyl);
  app.add_option("--center", o.center, "Axis of --cylinder (default: the centre of the part)")->type_name("X,Y");
  app.add_option("--width", o.formulas.width, "Factor on the bead's cross-section, a formula (default 1)")->type_name("FC");
  app.add_option("--speed", o.formulas.speed, "Factor on the head speed of extrusions, a formula (default 1)")->type_name("FV");
  app.add_flag("--keep-section", o.keep_section, "The cross-section is --width alone, not x dFZ/dz (the layers' new thickness)");
}

void add_limit_options(CLI::App& app, DeformToolOptions& o) {
  app.add_option("--tolerance", o.deform.tolerance, "Largest distance of the written path from the formula's image, mm")
      ->type_name("MM")->capture_default_str();
  app.add_option("--max-speed", o.deform.max_speed, "Cap on extrusion speed, mm/s (0 = none)")->type_name("MM_S")
      ->check(non_negative());
  app.add_option("--max-flow", o.deform.max_flow, "Cap on the extruder's volume rate, mm3/s (0 = none)")->type_name("MM3_S")
      ->check(non_negative());
  app.add_option("--filament-diameter", o.filament_diameter, "For --max-flow (default: the file's, else 1.75)")
      ->type_name("MM")->check(positive());
  app.add_option("--bed", o.bed, "The bed, from 0,0 (default: the slicer's SLIC3R_* or the file's)")->type_name("WxD");
  app.add_flag("--force", o.deform.force, "Print what dives into the part or jumps (never what leaves the bed); pass moves in inches unchanged");
}

void resolve(DeformToolOptions& o) {
  if (o.xyz.empty() && o.cylinder.empty()) throw UsageError("give the deformation: --xyz FX FY FZ or --cylinder FR FTHETA FZ");
  o.formulas.frame = o.xyz.empty() ? DeformFrame::Cylindrical : DeformFrame::Cartesian;
  const std::vector<std::string>& f = o.xyz.empty() ? o.cylinder : o.xyz;
  o.formulas.map = {f[0], f[1], f[2]};
  o.formulas.layer_scale = !o.keep_section;
  std::vector<double> c;
  if (!o.center.empty() && (!parse_number_list(o.center, c) || c.size() != 2))
    throw UsageError(fmt::format("--center: expected X,Y, not '{}'", o.center));
  if (c.size() == 2) o.formulas.center_x = c[0], o.formulas.center_y = c[1];
  if (!o.bed.empty() && !parse_bed_size(o.bed, o.deform.bed))
    throw UsageError(fmt::format("--bed: expected WIDTHxDEPTH in mm, not '{}'", o.bed));
  o.deform.has_bed = !o.bed.empty();
  try {
    o.deform.validate();
    DeformMap check(o.formulas);  // syntax and unknown names: a usage error with the position
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace

void add_deform_options(Tool& tool, DeformToolOptions& o) {
  tool.add_filter_options(o.io);
  add_map_options(tool.app(), o);
  add_limit_options(tool.app(), o);
  tool.check([&o] { resolve(o); });
}

}  // namespace gcode::cli
