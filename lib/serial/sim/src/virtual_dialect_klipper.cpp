// Klipper as a host meets it on its pseudo-terminal (klippy/gcode.py,
// gcode_move.py, toolhead.py): no greeting, line numbers and checksums
// read and ignored, an unknown command answered '// Unknown command:"X"'
// and ok, an error "!! ..." and ok, M115 answered on its ok line, and
// after a shutdown every command refused (with its ok) until
// FIRMWARE_RESTART. The printer modelled is one without [display],
// [display_status], [respond] or a second extruder: klippy unmodified
// then answers M73, M117, M118 and T0 '// Unknown command:"M117"' (seen on
// klippy v0.13 with a simulated board).
#include <array>
#include <string_view>

#include <fmt/format.h>

#include "gcode/core/firmware.hpp"
#include "gcode/core/line.hpp"
#include "gcode/serial/sim/virtual_dialect.hpp"
#include "gcode/serial/sim/virtual_printer_options.hpp"

namespace gcode::serial {

namespace {

// The standard commands of docs/G-Codes.md (with [gcode_arcs] and
// [firmware_retraction] configured, as on most printers). M73 and M117
// come with a display, M118 with [respond], T<n> with a second extruder.
constexpr CommandCode kKnown[] = {
    {'G', 0},   {'G', 1},   {'G', 2},   {'G', 3},   {'G', 4},   {'G', 10},  {'G', 11},
    {'G', 28},  {'G', 90},  {'G', 91},  {'G', 92},  {'M', 18},  {'M', 82},  {'M', 83},
    {'M', 84},  {'M', 104}, {'M', 105}, {'M', 106}, {'M', 107}, {'M', 109}, {'M', 110},
    {'M', 112}, {'M', 114}, {'M', 115}, {'M', 140}, {'M', 190}, {'M', 204}, {'M', 220},
    {'M', 221}, {'M', 400},
};

// Extended commands every Klipper has.
constexpr std::array<std::string_view, 6> kKnownExtended = {"FIRMWARE_RESTART", "RESTART", "STATUS", "HELP",
                                                            "SET_VELOCITY_LIMIT", "GET_POSITION"};

class KlipperDialect final : public ReplyDialect {
 public:
  const DialectBehaviour& behaviour() const override {
    static const DialectBehaviour b = [] {
      DialectBehaviour k;
      k.checks_line_numbers = false;
      k.busy_keepalive = false;
      k.buffer_seconds = 1.0;  // measured on klippy: a move's ok waits once about 1 s of motion is queued
      k.reads_everything = true;
      k.moves_need_homing = true;
      k.homing_failure_halts = false;  // homing.py raises a command error: "!! ...", then ok
      k.shutdown_answers = true;
      k.report_on_ok = true;
      k.empty_move_waits = false;  // answered at once: its queue is seconds of motion, not blocks
      return k;
    }();
    return b;
  }
  const FirmwareFlavor& firmware() const override { return klipper_firmware(); }
  std::string greeting() const override { return ""; }
  std::vector<std::string> restart_greeting(GreetingForm) const override { return {"// Klipper state: Ready"}; }
  std::string ok(long long, bool, int, int) const override { return "ok"; }

  bool knows(const Line& line) const override {
    if (line.kind == CommandKind::Host) return false;
    if (line.kind == CommandKind::Extended) {
      std::string_view code = line.code();
      code = code.substr(0, code.find(' '));
      for (std::string_view k : kKnownExtended)
        if (k == code) return true;
      return false;
    }
    for (const CommandCode& c : kKnown)
      if (line.is(c.letter, c.number)) return true;
    return false;
  }
  std::string unknown_command(std::string_view code) const override {
    return fmt::format("// Unknown command:\"{}\"", code.substr(0, code.find(' ')));
  }
  // homing.py's error when the endstop did not trigger.
  std::string homing_failed() const override { return "!! No trigger on x after full movement"; }
  std::string not_homed(double x, double y, double z, double e) const override {
    return fmt::format("!! Must home axis first: {:.3f} {:.3f} {:.3f} [{:.3f}]", x, y, z, e);
  }
  std::vector<std::string> refused_while_shut_down(std::string_view why) const override {
    // The state message as respond_info lines, then its first line as the
    // error (klippy.py's message_shutdown, word for word).
    return {fmt::format("// {}", why), "// Once the underlying issue is corrected, use the",
            "// \"FIRMWARE_RESTART\" command to reset the firmware, reload the",
            "// config, and restart the host software.", "// Printer is shutdown", fmt::format("!! {}", why)};
  }

  std::string temperatures(const Temperatures& t, bool) const override {
    // heaters.py: each sensor by its gcode id, sorted ("B" before "T0").
    return fmt::format("B:{:.1f} /{:.1f} T0:{:.1f} /{:.1f}", t.bed, t.bed_target, t.hotend, t.hotend_target);
  }
  std::string position(double x, double y, double z, double e, long, long, long) const override {
    return fmt::format("X:{:.3f} Y:{:.3f} Z:{:.3f} E:{:.3f}", x, y, z, e);
  }
  std::vector<std::string> firmware_report(const VirtualPrinterConfig& config) const override {
    return {fmt::format("ok FIRMWARE_NAME:Klipper FIRMWARE_VERSION:v0.12.0-gc-virtual-printer{}", link_report(config))};
  }
  std::string halted() const override { return "// Klipper state: Shutdown"; }
  std::string thermal_runaway() const override { return "// Heater extruder not heating at expected rate"; }
};

}  // namespace

const ReplyDialect& klipper_dialect() {
  static const KlipperDialect dialect;
  return dialect;
}

}  // namespace gcode::serial
