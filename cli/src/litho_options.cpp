#include "gcode/cli/litho_options.hpp"

#include <CLI/CLI.hpp>

#include <fmt/format.h>

#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string_view>

#include "gcode/core/number.hpp"

namespace gcode::cli {

namespace {

// Options that belong to one mode only: named in the other, a usage error.
void refuse(CLI::App& app, std::initializer_list<const char*> names, const char* why) {
  for (const char* n : names)
    if (app.get_option(n)->count() > 0) throw UsageError(fmt::format("{} {}", n, why));
}

std::string text_of(const std::string& path, const char* option) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{} {}: cannot open it", option, path));
  return {std::istreambuf_iterator<char>(in), {}};
}

// The option helpers of one group style: a length or a speed, with its default shown.
struct Adder {
  CLI::App& app;
  void mm(const char* name, double& v, const char* help, const char* group, bool zero = false) const {
    app.add_option(name, v, help)->type_name("MM")->check(zero ? non_negative() : positive())->capture_default_str()
        ->group(group);
  }
  void speed(const char* name, double& v, const char* help, const char* group) const {
    app.add_option(name, v, help)->type_name("MM_S")->check(positive())->capture_default_str()->group(group);
  }
};

void add_solid_options(const Adder& add, LithoToolOptions& o) {
  CLI::App& app = add.app;
  const char* shape = "Lithophane (mode 1): the solid";
  app.add_option("--shape", o.shape, "flat: a plate standing upright; cylinder: the picture wrapped around")
      ->type_name("flat|cylinder")->check(CLI::IsMember({"flat", "cylinder"}))->capture_default_str()->group(shape);
  add.mm("--diameter", o.map.diameter, "Cylinder: diameter of the inner (base) surface", shape);
  add.mm("--min", o.map.min_thickness, "Thickness where the picture is lightest", shape);
  add.mm("--max", o.map.max_thickness, "Thickness where the picture is darkest", shape);
  add.mm("--border", o.map.border, "Frame at full thickness around the picture (cylinder: top and bottom)", shape, true);
  app.add_flag("--invert", o.map.tone.invert, "Light = thick (mode 2: light = slow)")->group(shape);
  app.add_option("--gamma", o.map.tone.gamma, "Tone curve: > 1 prints the mid-tones thicker")->check(positive())
      ->capture_default_str()->group(shape);
  app.add_option("--contrast", o.map.tone.contrast, "Tone curve: > 1 more contrast about mid-grey")->check(positive())
      ->capture_default_str()->group(shape);
  const char* both = "Both modes";
  add.mm("--width", o.map.width, "Picture width (mode 1 default 100; cylinder: from --diameter; mode 2: once around for cylinder)", both, true);
  add.mm("--height", o.map.height, "Picture height (default: from the width and the picture's aspect)", both, true);
  add.mm("--resolution", o.plan.resolution, "Mode 1: sampling step along the path (pieces longer where straight; STL grid); mode 2: piece length", both);
  app.add_option("--center", o.center_text, "Where it stands on the bed (mode 2 sphere: X,Y,Z)")->type_name("X,Y")->group(both);
}

void add_path_options(const Adder& add, LithoToolOptions& o) {
  CLI::App& app = add.app;
  const char* path = "Lithophane (mode 1): the paths";
  add.mm("--layer-height", o.plan.layer_height, "Layer height", path);
  add.mm("--nozzle", o.plan.nozzle, "Nozzle diameter", path);
  add.mm("--line-width", o.plan.line_width, "Wall line width (0 = nozzle x 1.125)", path, true);
  add.mm("--filament-diameter", o.plan.filament_diameter, "Filament diameter", path);
  add.speed("--wall-speed", o.plan.wall_speed, "Speed of the walls", path);
  app.add_flag("--base-wall", o.plan.base_wall,
               "The base surface as a wall at --wall-speed, as the paper prints it (default: a bead at the passes' rate)")
      ->group(path);
  app.add_option("--infill-speed", o.plan.infill_speed,
                 "Conventional infill speed whose extruder rate the passes keep (0 = the rate is --max-flow)")
      ->type_name("MM_S")->check(non_negative())->capture_default_str()->group(path);
  app.add_option("--max-flow", o.plan.max_flow,
                 "The passes' extruder rate (the hot end's melt limit; a 0.4 mm E3D V6-class: 15 for PLA), mm3/s")
      ->type_name("MM3_S")->check(positive())->capture_default_str()->group(path);
  add.speed("--min-speed", o.plan.min_speed, "Slowest pass (slower: width kept, rate changes)", path);
  add.speed("--max-speed", o.plan.max_speed, "Fastest pass (faster: width kept, rate changes)", path);
  add.mm("--max-pass-width", o.plan.max_pass_width, "Wider gaps get more passes of equal width (0 = 2.5 x nozzle)", path, true);
  add.mm("--min-pass-width", o.plan.min_pass_width, "Narrower gaps get no pass (0 = 0.5 x nozzle)", path, true);
  const char* program = "Lithophane (mode 1): the program";
  app.add_option("--nozzle-temp", o.gcode.nozzle_temp, "Nozzle temperature, C")->capture_default_str()->group(program);
  app.add_option("--bed-temp", o.gcode.bed_temp, "Bed temperature, C")->capture_default_str()->group(program);
  app.add_option("--start", o.start, "Start G-code from FILE instead of the built-in Marlin start")->type_name("FILE")->group(program);
  app.add_option("--end", o.end, "End G-code from FILE instead of the built-in one")->type_name("FILE")->group(program);
  add.speed("--travel-speed", o.gcode.travel_speed, "Travel speed", program);
  add.mm("--retract", o.gcode.retract_length, "Retraction before travel that leaves the part, mm of filament (0 = none)", program, true);
  add.speed("--retract-speed", o.gcode.retract_speed, "Retraction speed", program);
  app.add_option("--stl", o.stl, "Also write the same lithophane as a binary STL")->type_name("FILE")->group(program);
}

// Returns --binary, whose presence the check needs.
CLI::Option* add_texture_options(const Adder& add, LithoToolOptions& o) {
  CLI::App& app = add.app;
  const char* paint = "Texture (mode 2): gc-litho --texture IMAGE [FILE]";
  app.add_option("--texture", o.texture, "Paint IMAGE onto the G-code read from FILE or standard input")
      ->type_name("IMAGE")->group(paint);
  app.add_option("--projection", o.projection, "How the picture falls on the print")->type_name("x|y|z|cylinder|sphere")
      ->check(CLI::IsMember({"x", "y", "z", "cylinder", "sphere"}))->capture_default_str()->group(paint);
  app.add_option("--bottom", o.mapping.bottom_z, "Height of the picture's bottom edge, mm")->capture_default_str()->group(paint);
  app.add_option("--offset", o.offset_text, "Move the picture right and up on its surface, mm")->type_name("U,V")->group(paint);
  app.add_flag("--stretch", o.stretch, "Do not keep the picture's aspect (give --width and --height)")->group(paint);
  add.speed("--low", o.speeds.low, "Speed for black", paint);
  add.speed("--high", o.speeds.high, "Speed for white (binary: the fast speed)", paint);
  CLI::Option* binary = app.add_option("--binary", o.speeds.threshold, "Two speeds: grey below THRESHOLD (0-1) is slow")
                            ->type_name("THRESHOLD")->group(paint);
  app.add_option("--ratio", o.speeds.ratio, "Binary: slow = --high x RATIO")->capture_default_str()->group(paint);
  app.add_option("--skip-z", o.skip_z, "Leave everything below this height alone, mm")->check(non_negative())->group(paint);
  return binary;
}

// Mode 2: the mapping and the speeds from the options.
void resolve_texture(CLI::App& app, LithoToolOptions& o, bool binary) {
  refuse(app, {"--shape", "--diameter", "--min", "--max", "--border", "--gamma", "--contrast", "--layer-height",
               "--nozzle", "--line-width", "--filament-diameter", "--wall-speed", "--base-wall", "--infill-speed", "--max-flow",
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
  o.speeds.binary = binary;
  o.speeds.invert = o.map.tone.invert;
  o.mapping.validate();  // std::invalid_argument in a check: a usage error
  o.speeds.validate();
}

// Mode 1: the height map, the planner's and the program's options.
void resolve_lithophane(CLI::App& app, LithoToolOptions& o) {
  refuse(app, {"--projection", "--bottom", "--offset", "--stretch", "--low", "--high", "--binary", "--ratio",
               "--skip-z", "--layers", "--z-range", "--types", "--layer-marker", "--e-mode"},
         "paints a picture onto G-code; it goes with --texture IMAGE");
  if (o.io.in_place) throw UsageError("-i replaces G-code; a lithophane is written to standard output or -o");
  if (!o.center.empty()) o.plan.center_x = o.center[0], o.plan.center_y = o.center[1];
  o.map.shape = o.shape == "cylinder" ? litho::LithoShape::Cylinder : litho::LithoShape::Flat;
  if (o.map.shape == litho::LithoShape::Cylinder && app.get_option("--width")->count() > 0)
    throw UsageError("--width: a cylinder's width is its circumference; give --diameter");
  o.map.validate();  // std::invalid_argument in a check: a usage error
  o.plan.validate(o.map);
  o.gcode.validate();
}

}  // namespace

void add_litho_options(Tool& tool, LithoToolOptions& o) {
  CLI::App& app = tool.app();
  tool.add_filter_options(o.io);
  app.get_option("FILE")->description("Mode 1: the picture (PNG, JPEG, BMP, PGM); mode 2: the G-code (- or absent: stdin)");
  const Adder add{app};
  add_solid_options(add, o);
  add_path_options(add, o);
  CLI::Option* binary = add_texture_options(add, o);
  tool.add_selection(o.where, "Paint only in");

  tool.check([&app, &o, binary] {
    auto numbers = [](const std::string& text, const char* name, const char* form, std::vector<double>& v) {
      const std::size_t most = std::string_view(form).ends_with(",Z") ? 3 : 2;  // a sphere's centre has a Z
      if (!text.empty() && (!parse_number_list(text, v) || v.size() < 2 || v.size() > most))
        throw UsageError(fmt::format("{}: expected {}, not '{}'", name, form, text));
    };
    numbers(o.center_text, "--center", o.painting() ? "X,Y or X,Y,Z" : "X,Y", o.center);
    numbers(o.offset_text, "--offset", "U,V", o.offset);
    if (o.painting())
      resolve_texture(app, o, binary->count() > 0);
    else
      resolve_lithophane(app, o);
  });
}

void load_litho_program(LithoToolOptions& o) {
  if (!o.start.empty()) o.gcode.start_code = text_of(o.gcode.start_name = o.start, "--start");
  if (!o.end.empty()) o.gcode.end_code = text_of(o.gcode.end_name = o.end, "--end");
}

litho::GreyImage load_picture(const std::string& path) {
  try {
    return litho::load_image(path);
  } catch (const litho::ImageError& e) {
    throw InputError(e.what());
  }
}

}  // namespace gcode::cli
