// gc-deform: any G-code bent by formulas, exact to a chord tolerance, its
// extrusion and speed following the deformation (background.md §2). The
// formulas, the cutting and the checks are the library's
// (transform/deform_map.hpp, transform/deform.hpp).
#include <fmt/format.h>

#include <sys/stat.h>

#include <cmath>
#include <optional>

#include "gcode/cli/deform_options.hpp"
#include "gcode/cli/filter.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/transform/deform.hpp"
#include "gcode/transform/deform_center.hpp"

namespace {

using gcode::cli::InputError;
using gcode::cli::UsageError;

using Options = gcode::cli::DeformToolOptions;

bool regular(int fd) {
  struct stat st {};
  return fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
}

// The part's centre: --center, the file's print box (Cura's ;MINX.., gc-shape's), or a first reading of a file.
void find_center(Options& o, gcode::cli::Filter& run, const gcode::PrintArea& area) {
  if (o.formulas.frame != gcode::DeformFrame::Cylindrical || !o.center.empty()) return;
  gcode::Point2 c;
  if (area.has_print_box) {
    c = area.print_box.centre();
  } else if (regular(run.input().fd())) {
    const int e_relative = run.e_mode() ? 1 : 0;
    if (!gcode::extrusion_centre(run.input().fd(), run.markers(), e_relative, c))
      throw InputError(fmt::format("{} extrudes nothing in its layers: give --center", run.input().name()));
    run.input().rewind();
  } else {
    throw UsageError("--cylinder on a pipe without the print's box in its header (;MINX: ...): give --center X,Y");
  }
  o.formulas.center_x = c.x, o.formulas.center_y = c.y;
}

int deform(Options& o, gcode::cli::Tool& tool) {
  gcode::Diagnostics diag = tool.diagnostics(o.io);
  gcode::cli::Filter run(o.io);
  const gcode::PrintArea area = run.print_area();
  if (o.bed.empty() && area.has_bed) o.deform.has_bed = true, o.deform.bed = area.bed;
  if (area.has_max_z) o.deform.has_max_z = true, o.deform.max_z = area.max_z;
  o.deform.filament_diameter = o.filament_diameter > 0 ? o.filament_diameter
                               : area.has_filament_diameter ? area.filament_diameter : 1.75;
  find_center(o, run, area);
  gcode::DeformMap map(o.formulas);
  gcode::Deformer stage(map, o.deform, run.pipeline().precision(), &diag);
  run.add(stage);
  run.write();
  const gcode::DeformStats& s = stage.stats();
  if (s.outside > 0)
    diag.warn(fmt::format("{} extrusion pieces have a cross-section factor outside {:g}-{:g} x the input's",
                          s.outside, o.deform.section_low, o.deform.section_high));
  if (s.moves > 0)
    diag.info(fmt::format("{} moves deformed into {} pieces ({} arcs), {} left as they were; cross-section factor "
                          "{:.3f}-{:.3f}, extrusion speed {:.1f}-{:.1f} mm/s ({} capped), {:.1f} mm of filament",
                          s.moves, s.pieces, s.arcs, s.unchanged, s.section_min, s.section_max, s.speed_min,
                          s.speed_max, s.capped, s.filament));
  else
    diag.info(fmt::format("nothing to deform: {} moves of the layers are their own image", s.unchanged));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  gcode::cli::Tool tool(
      "gc-deform",
      "gc-deform: bend any G-code by formulas, exact to a chord tolerance; E follows the deformed length and\n"
      "cross-section, F the speed factor. Formulas (muparser) use x y z or r theta z, layer, s (path mm), pi.\n"
      "  gc-shape helix --diameter 60 --height 80 | gc-deform --cylinder 'r + 1.05*z' theta '0.3*z' > dish.gcode\n"
      "  gc-deform --xyz 'x + 0.2*z*sqrt(abs(y-110)/30)' y z circle.gcode > heart.gcode");
  gcode::cli::add_deform_options(tool, o);
  return tool.run(argc, argv, [&] { return deform(o, tool); });
}
