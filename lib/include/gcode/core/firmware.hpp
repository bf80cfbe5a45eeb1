#pragma once
// What a printer's firmware does its own way, as one description with a
// named flag per quirk (ArcWelderLib's firmware layer is the model): how it
// reads modes, what its commands accept, which of them take long, how it
// answers on the serial line. Code that depends on a quirk asks the
// description instead of knowing Marlin, so the next flavour (Klipper's
// pseudo-terminal, Prusa, RepRapFirmware) is one more description in
// firmware.cpp and a name in find_firmware.
//
// Marlin 2 is the default everywhere: it is what the serial protocol and the
// tools were written against.
#include <span>
#include <string_view>

namespace gcode {

class Line;

// A command by letter and number (any subcode): G28, M109.
struct CommandCode {
  char letter;
  int number;
};

struct FirmwareFlavor {
  std::string_view name;  // as slicers name the flavour: "marlin2"

  // --- modes ---
  // G90/G91 set the E mode as well: on Marlin G90 makes E absolute again
  // even after M83 (a block that uses G91/G90 in a relative-E file must
  // re-issue M83). Klipper and RepRapFirmware leave E alone.
  bool g90_g91_set_e_mode = true;

  // --- M220, the speed factor ---
  bool m220_backup_restore = false;  // M220 B saves the factor, M220 R restores it
  bool m220_whole_percent = true;    // M220 S takes whole percents

  // --- how long a command's "ok" takes ---
  // After a time nothing in the file tells: heating waits, homing, probing
  // and levelling, dwell, waiting for the user.
  std::span<const CommandCode> unbounded;
  // Until the planner is empty: bounded by the moves before it, but long.
  std::span<const CommandCode> waits_for_moves;
  // At once, without waiting for the moves before it (others may wait until
  // the planner is empty; a host assumes they do).
  std::span<const CommandCode> instant;

  // --- the serial line ---
  // "N<n> ...*<checksum>" checked, a bad line answered with Error, Resend
  // and ok (Klipper's pseudo-terminal ignores numbers and checksums).
  bool checks_line_numbers = true;
  // "ok N<n> P<planner> B<queue>" when built with ADVANCED_OK.
  bool advanced_ok_possible = true;

  bool is_unbounded(const Line& line) const { return lists(unbounded, line); }
  bool waits_for_planner(const Line& line) const { return lists(waits_for_moves, line); }
  bool is_instant(const Line& line) const { return lists(instant, line); }
  // Unbounded or waiting for the planner: a host gives its answer more time.
  bool is_long_running(const Line& line) const { return is_unbounded(line) || waits_for_planner(line); }

 private:
  static bool lists(std::span<const CommandCode> codes, const Line& line);
};

// Marlin 2.x (also what gc-virtual-printer models).
const FirmwareFlavor& marlin2_firmware();
// Marlin 1.x: as Marlin 2 but without M220 B/R.
const FirmwareFlavor& marlin1_firmware();

// The description of a flavour as slicers name it (PrusaSlicer's
// gcode_flavor: "marlin2", "marlin" for Marlin 1 and older), case-insensitive;
// nullptr for a flavour not described yet.
const FirmwareFlavor* find_firmware(std::string_view flavor);

}  // namespace gcode
