#pragma once
// What the virtual printer (virtual_printer.hpp) says, and the few things
// its firmware does its own way (DialectBehaviour). Marlin's texts are the
// defaults of ReplyDialect (the protocol was written against Marlin); each
// other firmware is one file that overrides what it says differently:
// virtual_dialect_klipper.cpp (Klipper's pseudo-terminal: "!! ..." errors,
// '// Unknown command:"X"', no line numbers), virtual_dialect_prusa.cpp
// (Prusa-Firmware: "// action:paused", silent waits for the user),
// virtual_dialect_rrf.cpp (RepRapFirmware over USB: "Error: ...", "rs n").
//
// A dialect plays one firmware of the sender's list (core/firmware.hpp,
// firmwares()): the names --firmware and virtual:firmware= take are that
// list's. The two stay separate (what a host assumes, what a printer does);
// a test checks that they agree on every fact both hold.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/serial/sim/virtual_fault.hpp"

namespace gcode {
class Line;
struct FirmwareFlavor;
}

namespace gcode::serial {

struct VirtualPrinterConfig;

// What is wrong with a received line.
enum class LineFault : std::uint8_t {
  LineNumber,    // N is not the last line's + 1
  NoChecksum,    // N without *checksum (also a line cut at MAX_CMD_SIZE)
  Checksum,      // the checksum does not match
  NoLineNumber,  // *checksum without N
};

struct Temperatures {
  double hotend = 0, hotend_target = 0, bed = 0, bed_target = 0;
};

// What a firmware does its own way on the serial line (Marlin's by default).
struct DialectBehaviour {
  bool checks_line_numbers = true;  // false: "N12" and "*34" read and ignored, M110 does nothing (Klipper)
  bool busy_keepalive = true;       // "busy: processing" every 2 s while a command blocks
  // > 0: a move is taken while less than this much motion (seconds) is
  // queued (Klipper's toolhead, buffer_time_high); 0: while the planner has
  // a free block (Marlin).
  double buffer_seconds = 0;
  // Reads every byte as it comes and queues every line, however many: its
  // host process reads the pseudo-terminal into a list of its own
  // (Klipper). false: Marlin's RX buffer and BUFSIZE queue.
  bool reads_everything = false;
  // A move of no length (a bare G1) waits for a free planner block before
  // it is dropped, so its ok comes when a block ends (Marlin's
  // _buffer_steps); false: answered at once.
  bool empty_move_waits = true;
  bool moves_need_homing = false;   // a move before G28 is refused, with its ok (Klipper, RepRapFirmware)
  // A homing that does not reach its endstop kills the firmware (Marlin's
  // VALIDATE_HOMING_ENDSTOPS, on by default: kill(), "Printer halted");
  // false: G28 is answered with ReplyDialect::homing_failed() and its ok,
  // and the printer stays unhomed (Klipper).
  bool homing_failure_halts = true;
  // Halted, it still answers: every command refused with its ok until
  // FIRMWARE_RESTART (Klipper). false: it says nothing more (Marlin's kill()).
  bool shutdown_answers = false;
  bool report_on_ok = false;        // the answer to M115 is its ok line (Klipper)
  bool own_pause = false;           // M601 pauses until the user resumes, M602 resumes (Prusa)
  bool user_waits = false;          // M600 and "M115 U<newer>" wait for the user without a word (Prusa)
};

class ReplyDialect {
 public:
  virtual ~ReplyDialect() = default;
  virtual const DialectBehaviour& behaviour() const;
  // The firmware it plays, as the sender describes it (its name is what
  // --firmware and virtual:firmware= take).
  virtual const FirmwareFlavor& firmware() const;
  // Its version, as "M115 U<version>" is compared with it (Prusa).
  virtual std::string_view firmware_version() const { return "2.1.2"; }
  // The greeting at power-up ("": none, as on a pseudo-terminal).
  virtual std::string greeting() const { return "start"; }
  // The lines a board sends when it restarts, in one of the forms hosts meet.
  virtual std::vector<std::string> restart_greeting(GreetingForm form) const;
  // The answer to a command done; `number` -1: an unnumbered one. With
  // ADVANCED_OK the free planner blocks and queue slots.
  virtual std::string ok(long long number, bool advanced, int planner_free, int queue_free) const;
  // The answers to a bad line, the last good one being `last_line`.
  virtual std::vector<std::string> rejected(LineFault fault, long long last_line) const;
  // While a command blocks (Marlin's keepalive).
  virtual std::string busy() const { return "echo:busy: processing"; }
  // While idle, nothing queued (Marlin's NO_TIMEOUTS; idle_wait).
  virtual std::string idle() const { return "wait"; }
  // Whether it knows a command (Marlin: every standard one, no extended
  // command); an unknown one gets unknown_command() and its ok.
  virtual bool knows(const Line& line) const;
  virtual std::string unknown_command(std::string_view code) const;
  // A move before homing (behaviour().moves_need_homing), at the position given.
  virtual std::string not_homed(double x, double y, double z, double e) const;
  // The error before G28's ok when its homing failed (homing_failure_halts false).
  virtual std::string homing_failed() const { return "Error:Homing Failed"; }
  // A command refused while shut down (behaviour().shutdown_answers), `why`
  // the shutdown's reason; its ok follows.
  virtual std::vector<std::string> refused_while_shut_down(std::string_view why) const;
  // Its own pause began and ended (behaviour().own_pause).
  virtual std::string paused() const { return "// action:paused"; }
  virtual std::string resumed() const { return "// action:resumed"; }
  // A temperature report; `heating`: while M109/M190 waits.
  virtual std::string temperatures(const Temperatures& t, bool heating) const;
  // The answer to M105 (it carries its ok).
  virtual std::string temperature_ok(const Temperatures& t) const;
  // The answer to M114.
  virtual std::string position(double x, double y, double z, double e, long count_x, long count_y,
                               long count_z) const;
  // The answer to M115 (before its ok; with behaviour().report_on_ok, the ok line itself).
  virtual std::vector<std::string> firmware_report(const VirtualPrinterConfig& config) const;
  // M112, or kill() after a fatal error.
  virtual std::string halted() const { return "Error:Printer halted. kill() called!"; }
  // A heater failed (the halt follows).
  virtual std::string thermal_runaway() const { return "Error:Thermal Runaway, system stopped! Heater_ID: 0"; }

 protected:
  // " TIME_SCALE:20 BAUD:250000" when the config reports the link, else "".
  static std::string link_report(const VirtualPrinterConfig& config);
};

// Marlin 2's texts, exactly; Marlin 1's, the same but for its version.
const ReplyDialect& marlin_dialect();
const ReplyDialect& marlin1_dialect();
// Klipper's pseudo-terminal, Prusa-Firmware 3.x, RepRapFirmware 3 over USB.
const ReplyDialect& klipper_dialect();
const ReplyDialect& prusa_dialect();
const ReplyDialect& rrf_dialect();
// Every dialect the simulated printer has, one per firmware of firmwares().
std::span<const ReplyDialect* const> dialects();
// By a name of its firmware (find_firmware); nullptr for another.
const ReplyDialect* find_dialect(std::string_view name);

}  // namespace gcode::serial
