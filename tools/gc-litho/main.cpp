// gc-litho: lithophanes printed in one variable-width pass at a constant
// extruder rate (mode 1), and pictures painted onto a print by the head speed
// at a constant extruder rate (mode 2, --texture). The physics and the paths
// are the library's (litho/lithophane.hpp, litho/texture_stage.hpp).
#include <fmt/format.h>

#include <fstream>
#include <iterator>

#include "gcode/cli/filter.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/core/number.hpp"
#include "gcode/litho/litho_estimate.hpp"
#include "gcode/litho/stl_writer.hpp"
#include "gcode/litho/texture_stage.hpp"
#include "gcode/transform/subdivide.hpp"

namespace {

using gcode::cli::InputError;
using gcode::cli::UsageError;
namespace litho = gcode::litho;

struct Options {
  gcode::cli::FilterOptions io;
  gcode::SelectionText where;
  litho::HeightMapOptions map;
  litho::LithoOptions plan;
  litho::LithoGcodeOptions gcode;
  litho::TextureMapping mapping;
  litho::SpeedMapping speeds;
  std::string shape = "flat", projection = "cylinder", texture, stl, start, end;
  std::string center_text, offset_text;
  std::vector<double> center, offset;
  double skip_z = 0;
  bool stretch = false;
};

litho::GreyImage picture(const std::string& path) {
  try {
    return litho::load_image(path);
  } catch (const litho::ImageError& e) {
    throw InputError(e.what());
  }
}

std::string text_of(const std::string& path, const char* option) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{} {}: cannot open it", option, path));
  return {std::istreambuf_iterator<char>(in), {}};
}

// Options that belong to one mode only: named in the other, a usage error.
void refuse(CLI::App& app, std::initializer_list<const char*> names, const char* why) {
  for (const char* n : names)
    if (app.get_option(n)->count() > 0) throw UsageError(fmt::format("{} {}", n, why));
}

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
  if (!o.start.empty()) o.gcode.start_code = text_of(o.gcode.start_name = o.start, "--start");
  if (!o.end.empty()) o.gcode.end_code = text_of(o.gcode.end_name = o.end, "--end");
  const litho::HeightMap map(picture(o.gcode.image_name = o.io.file), o.map);
  const litho::LithophanePlanner planner(map, o.plan);
  library_check([&] { o.gcode.validate(); });
  o.gcode.estimated_seconds = litho::estimate_litho_seconds(planner, o.gcode);
  gcode::OutputFile file(o.io.output, "");
  std::optional<gcode::OutputBuffer> out(file.fd());
  const litho::LithoGcodeStats stats =
      litho::write_litho_gcode(planner, o.gcode, [&](std::string_view chunk) { out->write(chunk); });
  out->flush();
  file.commit();
  if (const std::uint64_t clamped = stats.clamped_fast + stats.clamped_slow; clamped > 0)
    diag.warn(fmt::format("{} of {} pieces clamped ({} to --max-speed, {} to --min-speed): their width was kept, "
                          "so their extruder rate differs from {:.3g} mm3/s",
                          clamped, stats.pieces, stats.clamped_fast, stats.clamped_slow, planner.fill_rate()));
  diag.info(fmt::format("{:.1f} x {:.1f} mm, {} layers, {:.2f} m of filament, {} pieces, estimated {}", map.length(),
                        map.height(), stats.layers, stats.filament / 1000, stats.pieces,
                        gcode::format_duration(o.gcode.estimated_seconds)));
  if (!o.stl.empty()) {
    const litho::StlOptions so{planner.options().resolution, o.plan.center_x, o.plan.center_y};
    gcode::OutputFile stl(o.stl, "");
    std::optional<gcode::OutputBuffer> out(stl.fd());
    const litho::StlStats st = litho::write_litho_stl(map, so, [&](std::string_view bytes) { out->write(bytes); });
    out->flush();
    stl.commit();
    diag.info(fmt::format("{}: {} triangles", o.stl, st.triangles));
  }
  return 0;
}

int texture(Options& o, gcode::cli::Tool& tool) {
  gcode::Diagnostics diag = tool.diagnostics(o.io);
  const litho::GreyImage image = picture(o.texture);
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
  CLI::App& app = tool.app();
  const auto &positive = gcode::cli::positive(), &non_negative = gcode::cli::non_negative();
  tool.add_filter_options(o.io);
  app.get_option("FILE")->description("Mode 1: the picture (PNG, JPEG, BMP, PGM); mode 2: the G-code (- or absent: stdin)");
  auto mm = [&](const char* name, double& v, const char* help, const char* group, bool zero = false) {
    app.add_option(name, v, help)->type_name("MM")->check(zero ? non_negative : positive)->capture_default_str()->group(group);
  };
  auto speed = [&](const char* name, double& v, const char* help, const char* group) {
    app.add_option(name, v, help)->type_name("MM_S")->check(positive)->capture_default_str()->group(group);
  };

  const char* shape = "Lithophane (mode 1): the solid";
  app.add_option("--shape", o.shape, "flat: a plate standing upright; cylinder: the picture wrapped around")
      ->type_name("flat|cylinder")->check(CLI::IsMember({"flat", "cylinder"}))->capture_default_str()->group(shape);
  mm("--diameter", o.map.diameter, "Cylinder: diameter of the inner (base) surface", shape);
  mm("--min", o.map.min_thickness, "Thickness where the picture is lightest", shape);
  mm("--max", o.map.max_thickness, "Thickness where the picture is darkest", shape);
  mm("--border", o.map.border, "Frame at full thickness around the picture (cylinder: top and bottom)", shape, true);
  app.add_flag("--invert", o.map.tone.invert, "Light = thick (mode 2: light = slow)")->group(shape);
  app.add_option("--gamma", o.map.tone.gamma, "Tone curve: > 1 prints the mid-tones thicker")->check(positive)
      ->capture_default_str()->group(shape);
  app.add_option("--contrast", o.map.tone.contrast, "Tone curve: > 1 more contrast about mid-grey")->check(positive)
      ->capture_default_str()->group(shape);
  const char* both = "Both modes";
  mm("--width", o.map.width, "Picture width (mode 1 default 100; cylinder: from --diameter; mode 2: once around for cylinder)", both, true);
  mm("--height", o.map.height, "Picture height (default: from the width and the picture's aspect)", both, true);
  mm("--resolution", o.plan.resolution, "Mode 1: sampling step along the path (pieces longer where straight; STL grid); mode 2: piece length", both);
  app.add_option("--center", o.center_text, "Where it stands on the bed (mode 2 sphere: X,Y,Z)")->type_name("X,Y")->group(both);
  const char* path = "Lithophane (mode 1): the paths";
  mm("--layer-height", o.plan.layer_height, "Layer height", path);
  mm("--nozzle", o.plan.nozzle, "Nozzle diameter", path);
  mm("--line-width", o.plan.line_width, "Wall line width (0 = nozzle x 1.125)", path, true);
  mm("--filament-diameter", o.plan.filament_diameter, "Filament diameter", path);
  speed("--wall-speed", o.plan.wall_speed, "Speed of both walls", path);
  speed("--infill-speed", o.plan.infill_speed, "Conventional infill speed that sets the passes' extruder rate", path);
  app.add_option("--max-flow", o.plan.max_flow, "Cap on the passes' extruder rate, mm3/s")->type_name("MM3_S")
      ->check(positive)->capture_default_str()->group(path);
  speed("--min-speed", o.plan.min_speed, "Slowest pass (slower: width kept, rate changes)", path);
  speed("--max-speed", o.plan.max_speed, "Fastest pass (faster: width kept, rate changes)", path);
  mm("--max-pass-width", o.plan.max_pass_width, "Wider gaps get more passes of equal width (0 = 2.5 x nozzle)", path, true);
  mm("--min-pass-width", o.plan.min_pass_width, "Narrower gaps get no pass (0 = 0.5 x nozzle)", path, true);
  const char* program = "Lithophane (mode 1): the program";
  app.add_option("--nozzle-temp", o.gcode.nozzle_temp, "Nozzle temperature, C")->capture_default_str()->group(program);
  app.add_option("--bed-temp", o.gcode.bed_temp, "Bed temperature, C")->capture_default_str()->group(program);
  app.add_option("--start", o.start, "Start G-code from FILE instead of the built-in Marlin start")->type_name("FILE")->group(program);
  app.add_option("--end", o.end, "End G-code from FILE instead of the built-in one")->type_name("FILE")->group(program);
  speed("--travel-speed", o.gcode.travel_speed, "Travel speed", program);
  mm("--retract", o.gcode.retract_length, "Retraction before travel that leaves the part, mm of filament (0 = none)", program, true);
  speed("--retract-speed", o.gcode.retract_speed, "Retraction speed", program);
  app.add_option("--stl", o.stl, "Also write the same lithophane as a binary STL")->type_name("FILE")->group(program);
  const char* paint = "Texture (mode 2): gc-litho --texture IMAGE [FILE]";
  app.add_option("--texture", o.texture, "Paint IMAGE onto the G-code read from FILE or standard input")
      ->type_name("IMAGE")->group(paint);
  app.add_option("--projection", o.projection, "How the picture falls on the print")->type_name("x|y|z|cylinder|sphere")
      ->check(CLI::IsMember({"x", "y", "z", "cylinder", "sphere"}))->capture_default_str()->group(paint);
  app.add_option("--bottom", o.mapping.bottom_z, "Height of the picture's bottom edge, mm")->capture_default_str()->group(paint);
  app.add_option("--offset", o.offset_text, "Move the picture right and up on its surface, mm")->type_name("U,V")->group(paint);
  app.add_flag("--stretch", o.stretch, "Do not keep the picture's aspect (give --width and --height)")->group(paint);
  speed("--low", o.speeds.low, "Speed for black", paint);
  speed("--high", o.speeds.high, "Speed for white (binary: the fast speed)", paint);
  auto* binary = app.add_option("--binary", o.speeds.threshold, "Two speeds: grey below THRESHOLD (0-1) is slow")
                     ->type_name("THRESHOLD")->group(paint);
  app.add_option("--ratio", o.speeds.ratio, "Binary: slow = --high x RATIO")->capture_default_str()->group(paint);
  app.add_option("--skip-z", o.skip_z, "Leave everything below this height alone, mm")->check(non_negative)->group(paint);
  tool.add_selection(o.where, "Paint only in");

  tool.check([&] {
    const bool painting = !o.texture.empty();
    auto numbers = [](const std::string& text, const char* name, const char* form, std::vector<double>& v) {
      const std::size_t most = std::string_view(form).ends_with(",Z") ? 3 : 2;  // a sphere's centre has a Z
      if (!text.empty() && (!gcode::parse_number_list(text, v) || v.size() < 2 || v.size() > most))
        throw UsageError(fmt::format("{}: expected {}, not '{}'", name, form, text));
    };
    numbers(o.center_text, "--center", painting ? "X,Y or X,Y,Z" : "X,Y", o.center);
    numbers(o.offset_text, "--offset", "U,V", o.offset);
    if (painting) {
      refuse(app, {"--shape", "--diameter", "--min", "--max", "--border", "--gamma", "--contrast", "--layer-height",
                   "--nozzle", "--line-width", "--filament-diameter", "--wall-speed", "--infill-speed", "--max-flow",
                   "--min-speed", "--max-speed", "--max-pass-width", "--min-pass-width", "--nozzle-temp",
                   "--bed-temp", "--start", "--end", "--travel-speed", "--retract", "--retract-speed", "--stl"},
             "makes a lithophane (mode 1); it does not go with --texture");
      litho::parse_projection(o.projection, o.mapping.projection);
      o.mapping.width = app.get_option("--width")->count() > 0 ? o.map.width : 0;
      o.mapping.height = o.map.height;
      o.mapping.keep_aspect = !o.stretch;
      if (o.offset.size() == 2) o.mapping.offset_u = o.offset[0], o.mapping.offset_v = o.offset[1];
      if (!o.center.empty()) o.mapping.center_x = o.center[0], o.mapping.center_y = o.center[1];
      if (o.center.size() == 3) o.mapping.center_z = o.center[2];
      if (o.skip_z > 0 && !o.where.z_range.empty()) throw UsageError("give --skip-z or --z-range, not both");
      if (o.skip_z > 0) o.where.z_range = fmt::format("{}:", o.skip_z);  // nothing below is even cut
      o.speeds.binary = binary->count() > 0;
      o.speeds.invert = o.map.tone.invert;
      library_check([&] { o.mapping.validate(), o.speeds.validate(); });
      return;
    }
    refuse(app, {"--projection", "--bottom", "--offset", "--stretch", "--low", "--high", "--binary", "--ratio",
                 "--skip-z", "--layers", "--z-range", "--types", "--layer-marker", "--e-mode"},
           "paints a picture onto G-code; it goes with --texture IMAGE");
    if (o.io.in_place) throw UsageError("-i replaces G-code; a lithophane is written to standard output or -o");
    if (!o.center.empty()) o.plan.center_x = o.center[0], o.plan.center_y = o.center[1];
    o.map.shape = o.shape == "cylinder" ? litho::LithoShape::Cylinder : litho::LithoShape::Flat;
    if (o.map.shape == litho::LithoShape::Cylinder && app.get_option("--width")->count() > 0)
      throw UsageError("--width: a cylinder's width is its circumference; give --diameter");
    library_check([&] { o.map.validate(), o.plan.validate(o.map), o.gcode.validate(); });
  });

  return tool.run(argc, argv, [&] { return o.texture.empty() ? lithophane(o, tool) : texture(o, tool); });
}
