#pragma once
// What a printer's firmware does its own way, as one description with a
// named flag per quirk (ArcWelderLib's firmware layer is the model): how it
// reads modes, what its commands accept, which of them take long, how it
// answers on the serial line. Code that depends on a quirk asks the
// description instead of knowing Marlin, so the next flavour is one more
// file (firmware_marlin.cpp, firmware_klipper.cpp, firmware_prusa.cpp,
// firmware_rrf.cpp) and its line in firmwares(), the one list of them.
//
// Marlin 2 is the default everywhere: it is what the serial protocol and the
// tools were written against.
#include <span>
#include <string>
#include <string_view>

namespace gcode {

class Line;

// A command by letter and number (any subcode): G28, M109; with
// `parameter` only when it has that word ("M115 U3.13.0").
struct CommandCode {
  char letter;
  int number;
  char parameter = 0;
};

struct FirmwareFlavor {
  std::string_view name;  // as slicers name the flavour: "marlin2"
  std::string_view also_named;  // another name for it ("rrf"), or ""
  // How its answer to M115 begins after "FIRMWARE_NAME:" ("Marlin 2.1.2",
  // "Klipper", "Prusa-Firmware 3.13.3 based on Marlin"): the flavour a host
  // detects (find_firmware_by_report). Empty: not detected that way.
  std::string_view reports_as;

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
  // "busy: processing" while a command blocks (Marlin's HOST_KEEPALIVE);
  // Klipper and RepRapFirmware say nothing until the command's ok.
  bool busy_keepalive = true;
  // Its ok means the command was read and queued, not that the planner
  // had room: Klipper's host answers at once until about 1 s of motion is
  // queued (then a move's ok waits for that second and its own time), so
  // the oks say nothing of the planner's blocks and the sender does not
  // pace moves on it (Sender::pacing).
  bool ok_when_queued = false;
  // A G1 that moves nothing waits for a free planner block before it is
  // dropped, so its ok says the planner had a block free then, and none
  // before if it came late (Marlin's Planner::_buffer_steps: the wait in
  // get_next_free_block comes before _populate_block drops a block of no
  // steps). The pacer (serial/pacer.hpp) asks with it. Not on deltas and
  // UBL's segmented moves (a move of no length returns before the planner):
  // the pacer only believes its answers once one has come late.
  bool empty_move_waits = false;
  // Sends "// action:paused" and "// action:resumed" when it pauses and
  // resumes itself (Prusa's M601/M602, its knob): a host holds its lines
  // and its timeouts meanwhile.
  bool reports_own_pause = false;

  bool is_unbounded(const Line& line) const { return lists(unbounded, line); }
  bool waits_for_planner(const Line& line) const { return lists(waits_for_moves, line); }
  bool is_instant(const Line& line) const { return lists(instant, line); }
  // Waits for someone at the printer and says nothing meanwhile (no
  // "busy:"): Prusa's M600 and "M115 U" with a newer version. A host that
  // timed them out would stop a healthy print.
  std::span<const CommandCode> silent_user_waits;

  bool waits_silently(const Line& line) const { return lists(silent_user_waits, line); }
  // Unbounded or waiting for the planner: a host gives its answer more time.
  bool is_long_running(const Line& line) const { return is_unbounded(line) || waits_for_planner(line); }

 private:
  static bool lists(std::span<const CommandCode> codes, const Line& line);
};

// Marlin 2.x (also what gc-virtual-printer models by default).
const FirmwareFlavor& marlin2_firmware();
// Marlin 1.x: as Marlin 2 but without M220 B/R.
const FirmwareFlavor& marlin1_firmware();
// Klipper's pseudo-terminal (/tmp/printer), firmware_klipper.cpp.
const FirmwareFlavor& klipper_firmware();
// Prusa-Firmware 3.x for the MK3/MK2.5/MINI family, firmware_prusa.cpp.
const FirmwareFlavor& prusa_firmware();
// RepRapFirmware 3 over USB, firmware_rrf.cpp.
const FirmwareFlavor& rrf_firmware();

// Every firmware described, the one list of them: find_firmware and
// find_firmware_by_report walk it, the tools name its names, and the
// simulated printer plays each (serial/virtual_dialect.hpp: a test checks
// that it has a dialect for every one, agreeing with its description).
std::span<const FirmwareFlavor* const> firmwares();
// Their names for a message or --help: "marlin2, marlin, klipper, prusa or
// reprapfirmware (rrf)".
std::string firmware_names();

// The description of a flavour as slicers name it (PrusaSlicer's
// gcode_flavor: "marlin2", "marlin" for Marlin 1 and older, "klipper",
// "reprapfirmware" or "rrf", and "prusa"), case-insensitive; nullptr for a
// flavour not described yet.
const FirmwareFlavor* find_firmware(std::string_view flavor);
// The description whose reports_as begins the FIRMWARE_NAME of an M115
// answer (blanks before it ignored); nullptr for a firmware not described.
const FirmwareFlavor* find_firmware_by_report(std::string_view firmware_name);

}  // namespace gcode
