// Prusa-Firmware 3.x (Marlin_main.cpp, messages.c): Marlin 1's protocol,
// a pause of its own (M601 parks and says "// action:paused", the user or
// M602 resumes, "// action:resumed") and waits for the user that say
// nothing (M600, and "M115 U<version>" newer than its own).
#include <fmt/format.h>

#include "gcode/core/firmware.hpp"
#include "gcode/serial/sim/virtual_dialect.hpp"
#include "gcode/serial/sim/virtual_printer_options.hpp"

namespace gcode::serial {

namespace {

class PrusaDialect final : public ReplyDialect {
 public:
  const DialectBehaviour& behaviour() const override {
    static const DialectBehaviour b = [] {
      DialectBehaviour p;
      p.own_pause = true;
      p.user_waits = true;
      p.empty_move_waits = false;  // not checked against Prusa-Firmware's planner: taken as answered at once
      return p;
    }();
    return b;
  }
  const FirmwareFlavor& firmware() const override { return prusa_firmware(); }
  std::string_view firmware_version() const override { return "3.13.3"; }
  std::string ok(long long, bool, int, int) const override { return "ok"; }  // no ADVANCED_OK

  std::string position(double x, double y, double z, double e, long, long, long) const override {
    // Prusa counts in millimetres.
    return fmt::format("X:{:.2f} Y:{:.2f} Z:{:.2f} E:{:.2f} Count X: {:.2f} Y:{:.2f} Z:{:.2f} E:{:.2f}", x, y, z, e, x,
                       y, z, e);
  }
  std::vector<std::string> firmware_report(const VirtualPrinterConfig& config) const override {
    return {fmt::format("FIRMWARE_NAME:Prusa-Firmware {} based on Marlin FIRMWARE_URL:"
                        "https://github.com/prusa3d/Prusa-Firmware PROTOCOL_VERSION:1.0 MACHINE_TYPE:Prusa i3 MK3S "
                        "EXTRUDER_COUNT:1{}",
                        firmware_version(), link_report(config)),
            "Cap:AUTOREPORT_TEMP:1", "Cap:AUTOREPORT_FANS:1", "Cap:AUTOREPORT_POSITION:1", "Cap:EXTENDED_M20:1"};
  }
};

}  // namespace

const ReplyDialect& prusa_dialect() {
  static const PrusaDialect dialect;
  return dialect;
}

}  // namespace gcode::serial
