#include "gcode/core/start_end_code.hpp"

#include <fmt/format.h>

#include "gcode/core/number.hpp"

namespace gcode {

namespace {

}  // namespace

std::string marlin_start_code(const MarlinStart& s) {
  std::string t;
  auto line = [&t](std::string_view l) {
    t.append(l);
    t.push_back('\n');
  };
  line(fmt::format("M140 S{} ; bed", number_string(s.bed_temp, 0)));
  line(fmt::format("M104 S{} ; nozzle", number_string(s.nozzle_temp, 0)));
  line(fmt::format("M190 S{}", number_string(s.bed_temp, 0)));
  line(fmt::format("M109 S{}", number_string(s.nozzle_temp, 0)));
  line("G28 ; home all axes");
  line("G90");
  line("M83 ; relative extrusion");
  line("M107");
  line(fmt::format("G0 F{} Z2", number_string(s.travel_speed * 60, 0)));
  line(fmt::format("G0 X{} Y{}", number_string(s.purge_x0, 3), number_string(s.purge_y, 3)));
  line(fmt::format("G0 Z{}", number_string(s.purge_z, 3)));
  line(fmt::format("G1 F1200 X{} E{} ; purge line", number_string(s.purge_x1, 3),
                   number_string(s.purge_filament, s.e_decimals)));
  return t;
}

std::string marlin_end_code(double lift_z) {
  return fmt::format("G0 F600 Z{} ; lift\nM104 S0\nM140 S0\nM107\nM84 ; motors off\n", number_string(lift_z, 3));
}

std::string with_final_newline(std::string text) {
  if (!text.empty() && text.back() != '\n') text.push_back('\n');
  return text;
}

}  // namespace gcode
