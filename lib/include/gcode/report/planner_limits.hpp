#pragma once
// The motion limits a firmware plans with: per-axis maximum feed rate and
// acceleration, the accelerations for printing, travel and retraction, and
// the cornering rule (classic jerk or junction deviation).
//
// Three sources, later ones overriding earlier ones:
//   1. Marlin's defaults (Configuration.h of Marlin 2.1, classic jerk on);
//   2. a profile of `key = value` lines (--profile, or the config block at the
//      end of a PrusaSlicer G-code file): our own keys, or
//      PrusaSlicer's (`machine_max_acceleration_x = 9000,1000`, first value =
//      normal mode), so a PrusaSlicer config.ini works as a profile as it is;
//   3. the limit commands in the G-code itself, as the firmware would obey
//      them: M201 M203 M204 M205 (Marlin), M566 and the mm/min M203 of
//      RepRapFirmware, M207 M208 (firmware retraction).
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/line.hpp"

namespace gcode {

enum class Firmware : unsigned char { Marlin, RepRapFirmware };

struct PlannerLimits {
  // Marlin 2.1 defaults: DEFAULT_MAX_FEEDRATE, DEFAULT_MAX_ACCELERATION,
  // DEFAULT_{,RETRACT_,TRAVEL_}ACCELERATION, DEFAULT_{X,Y,Z,E}JERK.
  std::array<double, 4> max_feedrate{300, 300, 5, 25};           // mm/s, X Y Z E
  std::array<double, 4> max_acceleration{3000, 3000, 100, 10000};  // mm/s^2
  double print_acceleration = 3000;    // M204 P (or S)
  double retract_acceleration = 3000;  // M204 R: E-only moves
  double travel_acceleration = 3000;   // M204 T (or S)
  // Caps on the three above, as PrusaSlicer's machine_max_acceleration_
  // extruding/retracting/travel: an M204 above the cap is clamped. 0 = none.
  double max_print_acceleration = 0;
  double max_retract_acceleration = 0;
  double max_travel_acceleration = 0;
  std::array<double, 4> jerk{10, 10, 0.3, 5};  // mm/s, classic jerk (M205 X Y Z E, M566/60)
  double junction_deviation = 0;              // mm, M205 J; > 0 selects that model
  double min_feedrate = 0;                    // mm/s, M205 S (printing moves)
  double min_travel_feedrate = 0;             // mm/s, M205 T (travel)
  // Firmware retraction (G10/G11): what the firmware does when the file does
  // not say (Marlin's FWRETRACT defaults; RepRapFirmware's 2 mm at 1000 mm/min
  // both ways once the firmware is known to be RRF), else M207 (S F, and RRF's
  // R T), M208 (Marlin: S F) or the profile's fw_* keys. Slicers do not time
  // these at all (PrusaSlicer) or at a fixed guess (CuraEngine): see the man page.
  double fw_retract_length = 3;       // mm
  double fw_retract_speed = 45;       // mm/s
  double fw_unretract_extra = 0;      // mm
  double fw_unretract_speed = 8;      // mm/s
  Firmware firmware = Firmware::Marlin;

  // Applies a limit command (M201 M203 M204 M205 M207 M208 M566); returns
  // whether the line was one. A first M566 means RepRapFirmware, whose M203
  // is in mm/min: an M203 read before it as mm/s is converted then, and
  // firmware retraction not yet set takes RRF's defaults.
  bool apply(const Line& line);

  // Applies one profile entry; returns false for an unknown key (ignored by
  // callers: a PrusaSlicer config has hundreds of other keys) and throws
  // std::invalid_argument for a known key with a bad value.
  bool set(std::string_view key, std::string_view value);
  // Reads a profile: `key = value` lines, optionally behind "; " (G-code
  // comments) or "#" comments. Returns the number of keys used; throws
  // std::runtime_error when the file cannot be read.
  // `path` may also name a built-in profile (see preset) when no such file exists.
  int load_profile(const std::string& path);
  int load_profile_text(std::string_view text);
  // Built-in profiles: "marlin" (the defaults above) and "cura" (CuraEngine's
  // fdmprinter machine defaults plus the way CuraEngine 4.13 counts firmware
  // retraction: what its ;TIME: assumes). Empty for an unknown name.
  static std::string_view preset(std::string_view name);
  // The PrusaSlicer config block at the end of a regular file (its last 64 kB,
  // read with pread: the file offset is left alone), applied as a profile
  // unless it says machine_limits_usage = ignore. Returns the keys used; 0
  // for a pipe or a file without the block.
  int load_file_config(int fd);

  // One line per group, for -v.
  std::vector<std::string> describe() const;

 private:
  void become_reprapfirmware();

  bool m203_in_mm_per_s_ = false;  // an M203 was read before the firmware was known
  bool fw_retract_set_ = false;    // M207/M208 or a fw_* profile key said how the printer retracts
};

}  // namespace gcode
