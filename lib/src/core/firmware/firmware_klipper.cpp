// Klipper's quirks as a host meets them on its pseudo-terminal (klippy's
// gcode.py, gcode_move.py, toolhead.py; docs/G-Codes.md).
#include "gcode/core/firmware.hpp"

namespace gcode {

namespace {

// Heating waits, homing and dwell: the ok comes when they are done, with
// temperature reports (M109/M190) or nothing at all in between.
constexpr CommandCode kKlipperUnbounded[] = {{'M', 109}, {'M', 190}, {'G', 28}, {'G', 4}};

constexpr CommandCode kKlipperWaitsForMoves[] = {{'M', 400}};

// Handled by the host at once (klippy queues the motion, not these).
constexpr CommandCode kKlipperInstant[] = {
    {'G', 90},  {'G', 91},  {'G', 92},  {'M', 73},  {'M', 82},  {'M', 83},  {'M', 104}, {'M', 105},
    {'M', 106}, {'M', 107}, {'M', 110}, {'M', 114}, {'M', 115}, {'M', 117}, {'M', 118}, {'M', 140},
    {'M', 204}, {'M', 220}, {'M', 221},
};

constexpr FirmwareFlavor klipper() {
  FirmwareFlavor f;
  f.name = "klipper";
  f.reports_as = "Klipper";          // "ok FIRMWARE_NAME:Klipper FIRMWARE_VERSION:v0.12.0-..."
  f.g90_g91_set_e_mode = false;      // G90 leaves M82/M83 alone (G91 makes E relative while it lasts)
  f.m220_backup_restore = false;     // M220 takes S only: "M220 B" would set 100 %
  f.m220_whole_percent = false;      // S is a float
  f.unbounded = kKlipperUnbounded;
  f.waits_for_moves = kKlipperWaitsForMoves;
  f.instant = kKlipperInstant;
  f.checks_line_numbers = false;     // "N12" and "*34" are read and ignored; M110 does nothing
  f.advanced_ok_possible = false;
  f.busy_keepalive = false;
  f.ok_when_queued = true;           // an ok waits once about 1 s of motion is queued (measured on klippy)
  f.reports_own_pause = false;
  return f;
}

constexpr FirmwareFlavor kKlipper = klipper();

}  // namespace

const FirmwareFlavor& klipper_firmware() { return kKlipper; }

}  // namespace gcode
