#include "gcode/cli/shape_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "gcode/core/number.hpp"

namespace gcode::cli {

namespace {

// A length in mm (> 0, or >= 0 where 0 means none) and a speed in mm/s, with their defaults in --help.
void add_mm(CLI::App& app, const char* name, double& v, const char* help, const char* group, bool zero = false) {
  app.add_option(name, v, help)->type_name("MM")->check(zero ? non_negative() : positive())->capture_default_str()->group(group);
}

void add_speed(CLI::App& app, const char* name, double& v, const char* help, const char* group) {
  app.add_option(name, v, help)->type_name("MM_S")->check(positive())->capture_default_str()->group(group);
}

void add_shape_group(CLI::App& app, ShapeToolOptions& o) {
  const char* shape = "The shape";
  procedural::ShapeOptions& s = o.shape;
  add_mm(app, "--diameter", s.diameter, "Diameter of the path (cone: at the bottom)", shape);
  add_mm(app, "--top-diameter", s.top_diameter, "Cone: diameter at the top", shape);
  add_mm(app, "--inner-diameter", s.inner_diameter, "Spiral: where it ends inside (0 = four line widths)", shape, true);
  add_mm(app, "--height", s.height, "Height of a rising shape (helix, cylinder, polygon, cone)", shape);
  app.add_option("--sides", s.sides, "Polygon: number of sides")->check(CLI::Range(3, 1000))->capture_default_str()->group(shape);
  app.add_option("--center", o.center, "Where the axis stands on the bed (default 110,110)")->type_name("X,Y")->group(shape);
  add_mm(app, "--tolerance", s.tolerance, "Largest distance of a chord from its curve", shape);
  const char* vase = "The vase from a mesh";
  app.add_option("--mesh", o.mesh, "Vase: the model, a binary or ASCII STL")->type_name("MODEL.stl")->group(vase);
  add_mm(app, "--scale", s.scale, "Vase: scale of the model's coordinates", vase);
  app.add_option("--bottom-layers", s.bottom_layers, "Vase: filled layers under the wall")
      ->check(CLI::Range(0, 1000))->capture_default_str()->group(vase);
  app.add_option("--bed", o.bed, "Vase: the printable volume, WIDTHxDEPTHxHEIGHT (default 220x220x250)")
      ->type_name("WxDxH")->group(vase);
  const char* bead = "The bead";
  add_mm(app, "--layer-height", s.layer_height, "Layer height: a rising spiral's pitch (shortened to whole turns)", bead);
  add_mm(app, "--line-width", s.line_width, "Line width (flat spirals: also the distance between turns)", bead);
  add_speed(app, "--speed", o.gcode.speed, "Print speed", bead);
  add_mm(app, "--filament-diameter", o.gcode.filament_diameter, "Filament diameter", bead);
}

void add_program_group(CLI::App& app, ShapeToolOptions& o) {
  const char* program = "The program";
  app.add_option("--nozzle-temp", o.gcode.nozzle_temp, "Nozzle temperature, C")->capture_default_str()->group(program);
  app.add_option("--bed-temp", o.gcode.bed_temp, "Bed temperature, C")->capture_default_str()->group(program);
  app.add_option("--fan", o.gcode.fan, "Fan from the second layer, 0-255")->capture_default_str()->group(program);
  app.add_option("--start", o.start, "Start G-code from FILE instead of the built-in Marlin start")->type_name("FILE")->group(program);
  app.add_option("--end", o.end, "End G-code from FILE instead of the built-in one")->type_name("FILE")->group(program);
  add_speed(app, "--travel-speed", o.gcode.travel_speed, "Travel speed", program);
  add_mm(app, "--retract", o.gcode.retract_length, "Retraction for the travel to the start and at the end, mm (0 = none)", program, true);
  add_speed(app, "--retract-speed", o.gcode.retract_speed, "Retraction speed", program);
}

void resolve_vase(ShapeToolOptions& o) {
  const bool vase = o.shape.kind == procedural::ShapeKind::Vase;
  if (vase && o.mesh.empty()) throw UsageError("vase: --mesh MODEL.stl is needed");
  if (!vase && !o.mesh.empty()) throw UsageError(fmt::format("--mesh makes a vase, not a {}", o.kind));
  if (o.bed.empty()) return;
  std::vector<double> size;
  std::string text = o.bed;
  std::replace(text.begin(), text.end(), 'x', ',');
  if (!parse_number_list(text, size) || size.size() != 3)
    throw UsageError(fmt::format("--bed: expected WIDTHxDEPTHxHEIGHT in mm, not '{}'", o.bed));
  o.shape.bed_width = size[0], o.shape.bed_depth = size[1], o.shape.bed_height = size[2];
}

void resolve(ShapeToolOptions& o) {
  procedural::parse_shape_kind(o.kind, o.shape.kind);
  resolve_vase(o);
  std::vector<double> c;
  if (!o.center.empty() && (!parse_number_list(o.center, c) || c.size() != 2))
    throw UsageError(fmt::format("--center: expected X,Y, not '{}'", o.center));
  if (c.size() == 2) o.shape.center_x = c[0], o.shape.center_y = c[1];
  try {
    o.shape.validate(), o.gcode.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace

void add_shape_options(Tool& tool, ShapeToolOptions& o) {
  CLI::App& app = tool.app();
  app.add_option("SHAPE", o.kind, "circle, spiral (flat), helix, cylinder (bottom + helix wall), polygon, cone, vase (--mesh)")
      ->required()->check(CLI::IsMember({"circle", "spiral", "helix", "cylinder", "polygon", "cone", "vase"}));
  tool.add_filter_options(o.io, kOutput | kVerbosity);
  add_shape_group(app, o);
  add_program_group(app, o);
  tool.check([&o] { resolve(o); });
}

}  // namespace gcode::cli
