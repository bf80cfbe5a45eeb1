// Prusa-Firmware 3.x (MK3S, MK2.5S): Marlin 1 at heart, with a pause of its
// own and waits for the user that say nothing (Marlin_main.cpp: M600,
// M601/M602, M115 U; its messages.c for the "// action:" texts).
#include "gcode/core/firmware.hpp"

namespace gcode {

namespace {

// Marlin's waits, and G80 (mesh bed levelling), G76 (PINDA calibration),
// M45 (XYZ calibration).
constexpr CommandCode kPrusaUnbounded[] = {
    {'M', 109}, {'M', 190}, {'M', 116}, {'M', 303}, {'M', 600}, {'M', 0},  {'M', 1},  {'M', 226},
    {'M', 45},  {'G', 28},  {'G', 29},  {'G', 30},  {'G', 4},   {'G', 80}, {'G', 76}, {'M', 115, 'U'},
};

// M600 waits for the new filament without "busy:"; "M115 U<version>" newer
// than the firmware asks the user to update, for up to 30 s.
constexpr CommandCode kPrusaSilentWaits[] = {{'M', 600}, {'M', 115, 'U'}};

constexpr CommandCode kPrusaWaitsForMoves[] = {{'M', 400}};

constexpr CommandCode kPrusaInstant[] = {
    {'G', 90},  {'G', 91},  {'G', 92},  {'G', 20},  {'G', 21},  {'M', 73},  {'M', 82},  {'M', 83},
    {'M', 104}, {'M', 105}, {'M', 106}, {'M', 107}, {'M', 110}, {'M', 117}, {'M', 140}, {'M', 155},
    {'M', 201}, {'M', 203}, {'M', 204}, {'M', 205}, {'M', 220}, {'M', 221}, {'M', 862},
};

constexpr FirmwareFlavor prusa() {
  FirmwareFlavor f;
  f.name = "prusa";
  f.reports_as = "Prusa-Firmware";   // "FIRMWARE_NAME:Prusa-Firmware 3.13.3 based on Marlin FIRMWARE_URL:..."
  f.g90_g91_set_e_mode = true;
  f.m220_backup_restore = true;      // M220 B/R, as Marlin 2
  f.m220_whole_percent = true;
  f.unbounded = kPrusaUnbounded;
  f.waits_for_moves = kPrusaWaitsForMoves;
  f.instant = kPrusaInstant;
  f.silent_user_waits = kPrusaSilentWaits;
  f.checks_line_numbers = true;
  f.advanced_ok_possible = false;
  f.busy_keepalive = true;           // G28, G80: "echo:busy: processing"; not M600
  f.ok_when_queued = false;
  f.reports_own_pause = true;        // M601 "// action:paused", M602 "// action:resumed"
  return f;
}

constexpr FirmwareFlavor kPrusa = prusa();

}  // namespace

const FirmwareFlavor& prusa_firmware() { return kPrusa; }

}  // namespace gcode
