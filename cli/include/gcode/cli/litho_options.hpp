#pragma once
// gc-litho's options and what they map to: mode 1 (FILE is a picture: a
// lithophane, litho/lithophane.hpp and litho_gcode.hpp) and mode 2
// (--texture IMAGE: a picture painted onto G-code, litho/texture_stage.hpp).
// An option of one mode named in the other is a usage error.
#include <string>
#include <vector>

#include "gcode/cli/tool.hpp"
#include "gcode/litho/height_map.hpp"
#include "gcode/litho/image.hpp"
#include "gcode/litho/litho_gcode.hpp"
#include "gcode/litho/lithophane.hpp"
#include "gcode/litho/texture.hpp"

namespace gcode::cli {

struct LithoToolOptions {
  FilterOptions io;
  SelectionText where;
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

  bool painting() const { return !texture.empty(); }
};

// Every option of both modes in its group, and the check after parsing that
// refuses the other mode's options and fills the mode's configuration
// (map, plan and gcode; or mapping and speeds), with the library's own
// checks as usage errors.
void add_litho_options(Tool& tool, LithoToolOptions& options);

// Mode 1's --start and --end files, read into options.gcode. Throws
// InputError when one cannot be opened.
void load_litho_program(LithoToolOptions& options);

// A picture, with a decoder's error as an InputError.
litho::GreyImage load_picture(const std::string& path);

}  // namespace gcode::cli
