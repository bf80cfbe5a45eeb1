#pragma once
// The built-in Marlin start and end code of the tools that write whole
// programs rather than filter one (gc-litho, gc-shape): heat the bed and the
// nozzle and wait, home, absolute positions with relative E (M83), fan off,
// and a purge line in front of the part at first-layer height; at the end,
// lift, heaters and fan off, motors off. A user's --start/--end text replaces
// them; `with_final_newline` makes such a text end its last line.
#include <string>

namespace gcode {

struct MarlinStart {
  double nozzle_temp = 210;  // C
  double bed_temp = 60;      // C
  double travel_speed = 150; // mm/s
  // The purge line: from (purge_x0, purge_y) to (purge_x1, purge_y) at purge_z,
  // pushing purge_filament mm of filament, written with e_decimals.
  double purge_x0 = 0, purge_x1 = 20, purge_y = 0, purge_z = 0.2;
  double purge_filament = 0;
  int e_decimals = 5;
};

// The lines, each ending in '\n'. The head ends at (purge_x1, purge_y, purge_z), E relative.
std::string marlin_start_code(const MarlinStart& start);
// The lines after the last move (and the caller's retraction): lift to
// `lift_z`, heaters and fan off, motors off.
std::string marlin_end_code(double lift_z);
// `text` with a '\n' after its last line (an empty text stays empty).
std::string with_final_newline(std::string text);

}  // namespace gcode
