// Marlin's quirks (a new firmware flavour is a file like this one, and a
// name in find_firmware, firmware.cpp).
#include "gcode/core/firmware.hpp"

namespace gcode {

namespace {

// Marlin's waits of unknown length: M109/M190/M191 heat, M116 waits for
// temperatures, M303 autotunes, M600 changes filament, M0/M1/M226 wait for
// the user, M48 probes repeatedly; G28 homes, G29 levels, G30 probes, G4
// dwells, G26 prints a mesh test, G33 calibrates a delta, G34 aligns Z, G12
// cleans the nozzle.
constexpr CommandCode kMarlinUnbounded[] = {
    {'M', 109}, {'M', 190}, {'M', 191}, {'M', 116}, {'M', 303}, {'M', 600}, {'M', 0},  {'M', 1},  {'M', 226},
    {'M', 48},  {'G', 28},  {'G', 29},  {'G', 30},  {'G', 4},   {'G', 26},  {'G', 33}, {'G', 34}, {'G', 12},
};

constexpr CommandCode kMarlinWaitsForMoves[] = {{'M', 400}};

// Answered as soon as Marlin reads them: modes, set position, targets
// without a wait, fans, messages, limits, factors.
constexpr CommandCode kMarlinInstant[] = {
    {'G', 90},  {'G', 91},  {'G', 92},  {'G', 20},  {'G', 21},  {'M', 73},  {'M', 82},  {'M', 83},
    {'M', 104}, {'M', 105}, {'M', 106}, {'M', 107}, {'M', 110}, {'M', 115}, {'M', 117}, {'M', 118},
    {'M', 140}, {'M', 141}, {'M', 155}, {'M', 201}, {'M', 203}, {'M', 204}, {'M', 205}, {'M', 220},
    {'M', 221},
};

constexpr FirmwareFlavor marlin(std::string_view name, std::string_view reports_as, bool m220_backup_restore) {
  FirmwareFlavor f;
  f.name = name;
  f.reports_as = reports_as;
  f.g90_g91_set_e_mode = true;
  f.m220_backup_restore = m220_backup_restore;
  f.m220_whole_percent = true;
  f.unbounded = kMarlinUnbounded;
  f.waits_for_moves = kMarlinWaitsForMoves;
  f.instant = kMarlinInstant;
  f.checks_line_numbers = true;
  f.advanced_ok_possible = true;
  f.busy_keepalive = true;
  f.ok_when_queued = false;
  f.reports_own_pause = false;
  f.empty_move_waits = true;
  return f;
}

constexpr FirmwareFlavor kMarlin2 = marlin("marlin2", "Marlin 2", true);
constexpr FirmwareFlavor kMarlin1 = marlin("marlin", "Marlin 1", false);

}  // namespace

const FirmwareFlavor& marlin2_firmware() { return kMarlin2; }
const FirmwareFlavor& marlin1_firmware() { return kMarlin1; }

}  // namespace gcode
