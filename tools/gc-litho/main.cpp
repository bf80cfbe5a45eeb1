// gc-litho: lithophanes printed in one variable-width pass at a constant
// extruder rate (mode 1), and pictures painted onto a print by the head speed
// at a constant extruder rate (mode 2, --texture). The physics and the paths
// are the library's (litho/lithophane.hpp, litho/texture_stage.hpp), the
// options cli/litho_options.hpp's.
#include <fmt/format.h>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/litho_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/litho/litho_estimate.hpp"
#include "gcode/litho/stl_writer.hpp"
#include "gcode/litho/texture_stage.hpp"
#include "gcode/transform/subdivide.hpp"

namespace {

using gcode::cli::UsageError;
using gcode::cli::load_picture;
using Options = gcode::cli::LithoToolOptions;
namespace litho = gcode::litho;

// The library's checks (std::invalid_argument) are usage errors.
template <typename F> void library_check(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

int lithophane(Options& o, gcode::cli::Tool& tool) {
  gcode::Diagnostics diag = tool.diagnostics(o.io);
  if (o.io.file.empty() || o.io.file == "-") throw UsageError("give the picture: gc-litho IMAGE [options]");
  gcode::cli::load_litho_program(o);
  const litho::HeightMap map(load_picture(o.gcode.image_name = o.io.file), o.map);
  const litho::LithophanePlanner planner(map, o.plan);
  library_check([&] { o.gcode.validate(); });
  o.gcode.estimated_seconds = litho::estimate_litho_seconds(planner, o.gcode);
  litho::LithoGcodeStats stats;
  gcode::cli::write_output_file(o.io.output, [&](gcode::OutputBuffer& out) {
    stats = litho::write_litho_gcode(planner, o.gcode, [&](std::string_view chunk) { out.write(chunk); });
  });
  // At q = --max-flow the narrowest beads run at --max-speed by design (info);
  // a bead too wide for --min-speed is worth a warning.
  if (stats.clamped_slow > 0)
    diag.warn(fmt::format("{} of {} pieces slowed to --min-speed: their width was kept, so their extruder rate is "
                          "below {:.3g} mm3/s", stats.clamped_slow, stats.pieces, planner.fill_rate()));
  if (stats.clamped_fast > 0)
    diag.info(fmt::format("{} of {} pieces at --max-speed (narrow beads: width kept, rate below {:.3g} mm3/s)",
                          stats.clamped_fast, stats.pieces, planner.fill_rate()));
  diag.info(fmt::format("{:.1f} x {:.1f} mm, {} layers, {:.2f} m of filament, {} pieces, estimated {}", map.length(),
                        map.height(), stats.layers, stats.filament / 1000, stats.pieces,
                        gcode::format_duration(o.gcode.estimated_seconds)));
  if (!o.stl.empty()) {
    const litho::StlOptions so{planner.options().resolution, o.plan.center_x, o.plan.center_y};
    litho::StlStats st;
    gcode::cli::write_output_file(o.stl, [&](gcode::OutputBuffer& out) {
      st = litho::write_litho_stl(map, so, [&](std::string_view bytes) { out.write(bytes); });
    });
    diag.info(fmt::format("{}: {} triangles", o.stl, st.triangles));
  }
  return 0;
}

int texture(Options& o, gcode::cli::Tool& tool) {
  gcode::Diagnostics diag = tool.diagnostics(o.io);
  const litho::GreyImage image = load_picture(o.texture);
  std::optional<litho::TextureProjection> projection;  // sized from the picture
  library_check([&] { projection.emplace(o.mapping, image.width(), image.height()); });
  const bool selected = !o.where.layers.empty() || !o.where.z_range.empty() || !o.where.types.empty();
  gcode::cli::Filter run(o.io);
  gcode::LayerSelection split_where, paint_where;
  if (selected) split_where = run.selection(o.where), paint_where = run.selection(o.where);
  // gc-subdivide's stage cuts the extrusions to the picture's resolution; travel stays whole.
  gcode::SubdivideOptions split{.max_length = o.plan.resolution, .split_travel = false};
  split.min_length = std::min(split.min_length, o.plan.resolution / 2);
  gcode::Subdivider subdivider(split, run.pipeline().precision(), &diag, selected ? &split_where : nullptr);
  litho::TextureStage stage(*projection, image, o.speeds, o.skip_z, run.pipeline().precision(),
                            selected ? &paint_where : nullptr,
                            litho::texture_parameters(o.texture, image, *projection, o.speeds, o.plan.resolution,
                                                      o.skip_z, o.where.types));
  run.add(subdivider), run.add(stage);
  run.write([&] { run.check_selection(paint_where, diag, "painted"); });
  const litho::TextureStats& s = stage.stats();
  if (s.textured == 0)
    diag.warn(fmt::format("the picture reaches none of the {} extrusions: check --center, --bottom, the size", s.extrusions));
  else if (o.mapping.projection == litho::Projection::Cylinder && s.spiral_layers * 2 < s.layers)
    diag.warn(fmt::format("note: {} is not a spiral (vase mode) print; the picture is painted on every extrusion it "
                          "reaches, layer by layer{}", run.input().name(),
                          o.where.types.empty() ? " (limit it with --types, e.g. --types WALL-OUTER)" : ""));
  diag.info(fmt::format("{} of {} extrusion pieces textured at {:.1f}-{:.1f} mm/s ({} off the picture); {} speed changes, "
                        "{} speeds restored, {} G92 E",
                        s.textured, s.extrusions, s.slowest, s.fastest, s.outside, s.speed_words, s.restores, s.resyncs));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  gcode::cli::Tool tool(
      "gc-litho",
      "gc-litho: lithophanes in one variable-width pass, and pictures painted by head speed, both at a constant\n"
      "extruder rate (bead area = extruder rate / head speed; the head answers at once, the extruder seconds late).\n"
      "  gc-litho photo.png --shape cylinder > litho.gcode        (mode 1: FILE is the picture)\n"
      "  gc-litho --texture face.png --height 60 < vase.gcode > painted.gcode   (mode 2: FILE is G-code)");
  gcode::cli::add_litho_options(tool, o);
  return tool.run(argc, argv, [&] { return o.painting() ? texture(o, tool) : lithophane(o, tool); });
}
