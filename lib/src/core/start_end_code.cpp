#include "gcode/core/start_end_code.hpp"

#include <fmt/format.h>

#include "gcode/core/number.hpp"

namespace gcode {

namespace {

std::string num(double v, int decimals = 3) {
  char b[kMaxNumberChars];
  return std::string(number_text(v, decimals, b));
}

}  // namespace

std::string marlin_start_code(const MarlinStart& s) {
  std::string t;
  auto line = [&t](std::string_view l) {
    t.append(l);
    t.push_back('\n');
  };
  line(fmt::format("M140 S{} ; bed", num(s.bed_temp, 0)));
  line(fmt::format("M104 S{} ; nozzle", num(s.nozzle_temp, 0)));
  line(fmt::format("M190 S{}", num(s.bed_temp, 0)));
  line(fmt::format("M109 S{}", num(s.nozzle_temp, 0)));
  line("G28 ; home all axes");
  line("G90");
  line("M83 ; relative extrusion");
  line("M107");
  line(fmt::format("G0 F{} Z2", num(s.travel_speed * 60, 0)));
  line(fmt::format("G0 X{} Y{}", num(s.purge_x0), num(s.purge_y)));
  line(fmt::format("G0 Z{}", num(s.purge_z)));
  line(fmt::format("G1 F1200 X{} E{} ; purge line", num(s.purge_x1), num(s.purge_filament, s.e_decimals)));
  return t;
}

std::string marlin_end_code(double lift_z) {
  return fmt::format("G0 F600 Z{} ; lift\nM104 S0\nM140 S0\nM107\nM84 ; motors off\n", num(lift_z));
}

std::string with_final_newline(std::string text) {
  if (!text.empty() && text.back() != '\n') text.push_back('\n');
  return text;
}

}  // namespace gcode
