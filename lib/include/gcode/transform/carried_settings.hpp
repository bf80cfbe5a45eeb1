#pragma once
// The printer settings a spliced stream carries across a seam beside the
// machine state: heater targets, fans, flow and pressure advance.
//
// A re-sliced file sets them in its start code (PrusaSlicer: "M104 S215",
// "M900 K0.04", "M221 S95"; Cura: "M140 S60", "M106 S255" at layer 2), and a
// block taken from the middle of it needs them although its start code is not
// printed. Heaters and fans are read as MachineState reads them
// (read_heater_fan, which keeps their numbers); a setting here is the line
// as written, so that a seam can write it again (RepRapFirmware's G10 P S R,
// Klipper's commands). Each kind of setting is one slot (per tool, fan or drive); a
// stream's slots hold the last line that set them, so a seam writes exactly
// the lines that differ between what the printer was told and what the next
// block expects.
//
//   hotend   M104/M109 [T] S|R, RepRapFirmware G10 P S, M568 P S
//   bed      M140/M190 S|R          chamber  M141/M191 S|R
//   fan      M106 [P] [S], M107 [P]
//   flow     M221 [T] S
//   advance  M900 [T] K (Marlin linear advance), M572 D S (RepRapFirmware),
//            SET_PRESSURE_ADVANCE ... (Klipper)
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/fixed.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/machine_state.hpp"

namespace gcode {

class CarriedSettings {
 public:
  enum class Kind : std::uint8_t { Bed, Chamber, Hotend, Fan, Flow, Advance };

  struct Setting {
    Kind kind = Kind::Hotend;
    int index = 0;        // tool, fan or drive
    std::string command;  // the command that set it (M900, M572, SET_PRESSURE_ADVANCE ...)
    Fixed value;          // the target, speed, factor or coefficient (commands by text: 0)
    std::string text;     // the line's code as written ("M109 S215", "M900 K0.04")
  };

  // Whether a line may set something carried: one look at its command, so
  // every line of a stream can be asked.
  static bool may_set(const Line& line) {
    if (line.kind == CommandKind::Standard) {
      if (line.letter == 'M') {
        switch (line.number) {
          case 104: case 109: case 140: case 190: case 141: case 191:
          case 106: case 107: case 221: case 568: case 572: case 900: return true;
          default: return false;
        }
      }
      return line.letter == 'G' && line.number == 10 && line.has('P') && line.has('S');
    }
    return line.kind == CommandKind::Extended;
  }

  // Records `line` when it sets something carried; `tool` is the active
  // tool (M104 without T). Returns whether it did.
  bool observe(const Line& line, int tool);

  // Takes every slot `other` holds (after a seam wrote the differences).
  void adopt(const CarriedSettings& other) {
    for (const Setting& s : other.settings_) set(s);
  }

  const std::vector<Setting>& all() const { return settings_; }
  const Setting* find(Kind kind, int index, std::string_view command = {}) const;
  bool empty() const { return settings_.empty(); }

  // The lines that make a printer set as `from` set as this: for every slot
  // this holds that `from` lacks or holds at another value, in this order:
  // bed, chamber, hotends, fans, flow, advance. Heaters are written as
  // targets to wait for when they rise (M190, M109: the block must not start
  // cold) and as plain targets when they fall; the rest as their lines were
  // written. `tool` is the active tool (a hotend line names any other).
  std::vector<std::string> lines_from(const CarriedSettings& from, int tool) const;

  friend bool operator==(const CarriedSettings& a, const CarriedSettings& b);

 private:
  void set(Setting s);
  std::vector<Setting> settings_;
};

}  // namespace gcode
