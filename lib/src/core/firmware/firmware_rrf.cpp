// RepRapFirmware 3 over USB (Duet3D's G-code reference): "ok" after each
// command, its errors as "Error: ..." lines before that ok, no keepalive.
#include "gcode/core/firmware.hpp"

namespace gcode {

namespace {

// Heating waits, homing and probing (G29 mesh, G30 probe, G32 true
// bed levelling), dwell, M226 pause.
constexpr CommandCode kRrfUnbounded[] = {{'M', 109}, {'M', 190}, {'M', 116}, {'M', 226}, {'M', 600}, {'G', 28},
                                         {'G', 29},  {'G', 30},  {'G', 32},  {'G', 4}};

constexpr CommandCode kRrfWaitsForMoves[] = {{'M', 400}};

constexpr CommandCode kRrfInstant[] = {
    {'G', 90},  {'G', 91},  {'G', 92},  {'G', 20},  {'G', 21},  {'M', 73},  {'M', 82},  {'M', 83},
    {'M', 104}, {'M', 105}, {'M', 106}, {'M', 107}, {'M', 110}, {'M', 115}, {'M', 117}, {'M', 118},
    {'M', 140}, {'M', 201}, {'M', 203}, {'M', 204}, {'M', 220}, {'M', 221}, {'M', 566},
};

constexpr FirmwareFlavor rrf() {
  FirmwareFlavor f;
  f.name = "reprapfirmware";
  f.also_named = "rrf";
  f.reports_as = "RepRapFirmware";   // "FIRMWARE_NAME: RepRapFirmware for Duet 3 MB6HC FIRMWARE_VERSION: 3.5.1 ..."
  f.g90_g91_set_e_mode = false;
  f.m220_backup_restore = false;
  f.m220_whole_percent = false;
  f.unbounded = kRrfUnbounded;
  f.waits_for_moves = kRrfWaitsForMoves;
  f.instant = kRrfInstant;
  f.checks_line_numbers = true;      // a bad line is answered "rs <n>" (M998)
  f.advanced_ok_possible = false;
  f.busy_keepalive = false;
  f.ok_when_queued = false;
  f.reports_own_pause = false;
  return f;
}

constexpr FirmwareFlavor kRrf = rrf();

}  // namespace

const FirmwareFlavor& rrf_firmware() { return kRrf; }

}  // namespace gcode
