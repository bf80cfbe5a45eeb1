// RepRapFirmware 3 over USB (Duet3D's G-code reference): no greeting, "ok"
// after every command, errors as "Error: ..." before that ok, a bad line
// answered "rs <n>" (its M998), no keepalive, moves refused before homing.
#include <fmt/format.h>

#include "gcode/core/firmware.hpp"
#include "gcode/core/line.hpp"
#include "gcode/serial/sim/virtual_dialect.hpp"
#include "gcode/serial/sim/virtual_printer_options.hpp"

namespace gcode::serial {

namespace {

class RrfDialect final : public ReplyDialect {
 public:
  const DialectBehaviour& behaviour() const override {
    static const DialectBehaviour b = [] {
      DialectBehaviour r;
      r.busy_keepalive = false;
      r.moves_need_homing = true;  // M564 H1, the default since 1.21
      r.homing_failure_halts = false;  // not checked against RepRapFirmware: an error, then ok
      r.empty_move_waits = false;  // not checked against RepRapFirmware: taken as answered at once
      return r;
    }();
    return b;
  }
  const FirmwareFlavor& firmware() const override { return rrf_firmware(); }
  std::string greeting() const override { return ""; }
  std::vector<std::string> restart_greeting(GreetingForm) const override { return {}; }
  std::string ok(long long, bool, int, int) const override { return "ok"; }
  std::vector<std::string> rejected(LineFault, long long last_line) const override {
    return {fmt::format("rs {}", last_line + 1), "ok"};
  }

  bool knows(const Line& line) const override {
    // Prusa's printer checks and Marlin's linear advance (RRF has M572) are not its own.
    if (line.is_m(862) || line.is_m(900) || line.is('G', 80)) return false;
    return ReplyDialect::knows(line);
  }
  std::string unknown_command(std::string_view code) const override {
    return fmt::format("Error: {}: command is not supported", code.substr(0, code.find(' ')));
  }
  std::string not_homed(double, double, double, double) const override {
    return "Error: G0/G1: insufficient axes homed";
  }

  std::string temperatures(const Temperatures& t, bool) const override {
    return fmt::format("T:{:.1f} /{:.1f} B:{:.1f} /{:.1f}", t.hotend, t.hotend_target, t.bed, t.bed_target);
  }
  std::string position(double x, double y, double z, double e, long cx, long cy, long cz) const override {
    return fmt::format("X:{:.3f} Y:{:.3f} Z:{:.3f} E:{:.3f} E0:{:.1f} Count {} {} {} Machine {:.3f} {:.3f} {:.3f} "
                       "Bed comp 0.000",
                       x, y, z, e, e, cx, cy, cz, x, y, z);
  }
  std::vector<std::string> firmware_report(const VirtualPrinterConfig& config) const override {
    return {fmt::format("FIRMWARE_NAME: RepRapFirmware for Duet 3 MB6HC (gc-virtual-printer) FIRMWARE_VERSION: 3.5.1 "
                        "ELECTRONICS: Duet 3 MB6HC v1.01 FIRMWARE_DATE: 2024-04-19{}",
                        link_report(config))};
  }
  std::string halted() const override { return "Error: Emergency stop, the controller restarts"; }
  std::string thermal_runaway() const override { return "Error: Heater 1 fault: temperature rising too slowly"; }
};

}  // namespace

const ReplyDialect& rrf_dialect() {
  static const RrfDialect dialect;
  return dialect;
}

}  // namespace gcode::serial
