// gc-shape: printable primitives without a slicer, each one seamless path
// (background.md §2). The geometry and the G-code are the library's
// (procedural/shape.hpp, procedural/shape_gcode.hpp).
#include <fmt/format.h>

#include <fstream>
#include <iterator>
#include <optional>

#include "gcode/core/file_io.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/output_buffer.hpp"
#include "gcode/procedural/shape_gcode.hpp"

namespace {

using gcode::cli::UsageError;
namespace procedural = gcode::procedural;

struct Options {
  gcode::cli::FilterOptions io;
  procedural::ShapeOptions shape;
  procedural::ShapeGcodeOptions gcode;
  std::string kind, center, start, end;
};

std::string text_of(const std::string& path, const char* option) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw gcode::cli::InputError(fmt::format("{} {}: cannot open it", option, path));
  return {std::istreambuf_iterator<char>(in), {}};
}

int write(Options& o, gcode::cli::Tool& tool) {
  gcode::Diagnostics diag = tool.diagnostics(o.io);
  if (!o.start.empty()) o.gcode.start_code = text_of(o.gcode.start_name = o.start, "--start");
  if (!o.end.empty()) o.gcode.end_code = text_of(o.gcode.end_name = o.end, "--end");
  const procedural::ShapePath path(o.shape);
  gcode::OutputFile file(o.io.output, "");
  std::optional<gcode::OutputBuffer> out(file.fd());
  const procedural::ShapeGcodeStats stats =
      procedural::write_shape_gcode(path, o.gcode, [&](std::string_view chunk) { out->write(chunk); });
  out->flush();
  file.commit();
  diag.info(fmt::format("{}: {} layers, {} moves, {:.2f} m of path, {:.3f} m of filament", o.kind, stats.layers,
                        stats.moves, stats.length / 1000, stats.filament / 1000));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  gcode::cli::Tool tool(
      "gc-shape",
      "gc-shape: primitives printed without a slicer, each one seamless path; a rising spiral has no seam and no\n"
      "layer change (one turn = one layer). Diameters are the path's centre line.\n"
      "  gc-shape helix --diameter 60 --height 80 > cup.gcode\n"
      "  gc-shape cylinder --diameter 40 --height 30 | gc-deform --cylinder 'r + 1.05*z' theta '0.3*z' > dish.gcode");
  CLI::App& app = tool.app();
  const auto &positive = gcode::cli::positive(), &non_negative = gcode::cli::non_negative();
  app.add_option("SHAPE", o.kind, "circle, spiral (flat), helix, cylinder (bottom + helix wall), polygon, cone")
      ->required()->check(CLI::IsMember({"circle", "spiral", "helix", "cylinder", "polygon", "cone"}));
  tool.add_filter_options(o.io, gcode::cli::kOutput | gcode::cli::kVerbosity);
  auto mm = [&](const char* name, double& v, const char* help, const char* group, bool zero = false) {
    app.add_option(name, v, help)->type_name("MM")->check(zero ? non_negative : positive)->capture_default_str()->group(group);
  };
  auto speed = [&](const char* name, double& v, const char* help, const char* group) {
    app.add_option(name, v, help)->type_name("MM_S")->check(positive)->capture_default_str()->group(group);
  };
  const char* shape = "The shape";
  procedural::ShapeOptions& s = o.shape;
  mm("--diameter", s.diameter, "Diameter of the path (cone: at the bottom)", shape);
  mm("--top-diameter", s.top_diameter, "Cone: diameter at the top", shape);
  mm("--inner-diameter", s.inner_diameter, "Spiral: where it ends inside (0 = four line widths)", shape, true);
  mm("--height", s.height, "Height of a rising shape (helix, cylinder, polygon, cone)", shape);
  app.add_option("--sides", s.sides, "Polygon: number of sides")->check(CLI::Range(3, 1000))->capture_default_str()->group(shape);
  app.add_option("--center", o.center, "Where the axis stands on the bed (default 110,110)")->type_name("X,Y")->group(shape);
  mm("--tolerance", s.tolerance, "Largest distance of a chord from its curve", shape);
  const char* bead = "The bead";
  mm("--layer-height", s.layer_height, "Layer height: a rising spiral's pitch (shortened to whole turns)", bead);
  mm("--line-width", s.line_width, "Line width (flat spirals: also the distance between turns)", bead);
  speed("--speed", o.gcode.speed, "Print speed", bead);
  mm("--filament-diameter", o.gcode.filament_diameter, "Filament diameter", bead);
  const char* program = "The program";
  app.add_option("--nozzle-temp", o.gcode.nozzle_temp, "Nozzle temperature, C")->capture_default_str()->group(program);
  app.add_option("--bed-temp", o.gcode.bed_temp, "Bed temperature, C")->capture_default_str()->group(program);
  app.add_option("--fan", o.gcode.fan, "Fan from the second layer, 0-255")->capture_default_str()->group(program);
  app.add_option("--start", o.start, "Start G-code from FILE instead of the built-in Marlin start")->type_name("FILE")->group(program);
  app.add_option("--end", o.end, "End G-code from FILE instead of the built-in one")->type_name("FILE")->group(program);
  speed("--travel-speed", o.gcode.travel_speed, "Travel speed", program);
  mm("--retract", o.gcode.retract_length, "Retraction for the travel to the start and at the end, mm (0 = none)", program, true);
  speed("--retract-speed", o.gcode.retract_speed, "Retraction speed", program);

  tool.check([&] {
    procedural::parse_shape_kind(o.kind, s.kind);
    std::vector<double> c;
    if (!o.center.empty() && (!gcode::parse_number_list(o.center, c) || c.size() != 2))
      throw UsageError(fmt::format("--center: expected X,Y, not '{}'", o.center));
    if (c.size() == 2) s.center_x = c[0], s.center_y = c[1];
    try {
      s.validate(), o.gcode.validate();
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  });
  return tool.run(argc, argv, [&] { return write(o, tool); });
}
