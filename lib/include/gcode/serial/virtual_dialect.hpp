#pragma once
// What the virtual printer (virtual_printer.hpp) says, apart from what it
// does: the texts of its answers. Marlin's are here; another firmware's
// dialect (Klipper's "!! ..." errors and "// Unknown command", Prusa's
// "// action:paused", RepRapFirmware's) is another implementation.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/serial/virtual_fault.hpp"

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

class ReplyDialect {
 public:
  virtual ~ReplyDialect() = default;
  // The greeting at power-up.
  virtual std::string greeting() const = 0;
  // The lines a board sends when it restarts, in one of the forms hosts meet.
  virtual std::vector<std::string> restart_greeting(GreetingForm form) const = 0;
  // The answer to a command done; `number` -1: an unnumbered one. With
  // ADVANCED_OK the free planner blocks and queue slots.
  virtual std::string ok(long long number, bool advanced, int planner_free, int queue_free) const = 0;
  // The answers to a bad line, the last good one being `last_line`.
  virtual std::vector<std::string> rejected(LineFault fault, long long last_line) const = 0;
  // While a command blocks (Marlin's keepalive).
  virtual std::string busy() const = 0;
  virtual std::string unknown_command(std::string_view code) const = 0;
  // A temperature report; `heating`: while M109/M190 waits.
  virtual std::string temperatures(const Temperatures& t, bool heating) const = 0;
  // The answer to M105 (it carries its ok).
  virtual std::string temperature_ok(const Temperatures& t) const = 0;
  // The answer to M114.
  virtual std::string position(double x, double y, double z, double e, long count_x, long count_y,
                               long count_z) const = 0;
  // The answer to M115 (before its ok).
  virtual std::vector<std::string> firmware_report(const VirtualPrinterConfig& config) const = 0;
  // M112, or kill() after a fatal error.
  virtual std::string halted() const = 0;
  // A heater failed (the halt follows).
  virtual std::string thermal_runaway() const = 0;
};

// Marlin 2's texts, exactly.
const ReplyDialect& marlin_dialect();

}  // namespace gcode::serial
