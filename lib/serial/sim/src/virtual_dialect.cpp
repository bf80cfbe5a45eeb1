// Marlin 2's texts, the defaults every other dialect starts from, and the
// dialects by name.
#include "gcode/serial/sim/virtual_dialect.hpp"

#include <fmt/format.h>

#include "gcode/core/firmware.hpp"
#include "gcode/core/line.hpp"
#include "gcode/serial/sim/virtual_printer_options.hpp"

namespace gcode::serial {

const FirmwareFlavor& ReplyDialect::firmware() const { return marlin2_firmware(); }

const DialectBehaviour& ReplyDialect::behaviour() const {
  static const DialectBehaviour marlin;
  return marlin;
}

std::vector<std::string> ReplyDialect::restart_greeting(GreetingForm form) const {
  switch (form) {
    // A USB-serial chip often hands over a NUL (line noise of the reset) first.
    case GreetingForm::NulStart: return {std::string("\0start", 6)};
    case GreetingForm::Twice: return {"start", "start"};
    case GreetingForm::ExternalReset:
      return {"start", "echo: External Reset", fmt::format("Marlin {} (gc-virtual-printer)", firmware_version())};
    case GreetingForm::Start:
    case GreetingForm::CutLine: break;  // the printer puts the cut line before it
  }
  return {"start"};
}

std::string ReplyDialect::ok(long long number, bool advanced, int planner_free, int queue_free) const {
  if (!advanced) return "ok";
  if (number >= 0) return fmt::format("ok N{} P{} B{}", number, planner_free, queue_free);
  return fmt::format("ok P{} B{}", planner_free, queue_free);
}

std::vector<std::string> ReplyDialect::rejected(LineFault fault, long long last_line) const {
  const char* message = "";
  switch (fault) {
    case LineFault::LineNumber: message = "Line Number is not Last Line Number+1, Last Line: "; break;
    case LineFault::NoChecksum: message = "No Checksum with line number, Last Line: "; break;
    case LineFault::Checksum: message = "checksum mismatch, Last Line: "; break;
    case LineFault::NoLineNumber: message = "No Line Number with checksum, Last Line: "; break;
  }
  return {fmt::format("Error:{}{}", message, last_line), fmt::format("Resend: {}", last_line + 1), "ok"};
}

bool ReplyDialect::knows(const Line& line) const {
  // Klipper-style extended commands and host commands: Marlin knows none.
  return line.kind != CommandKind::Extended && line.kind != CommandKind::Host;
}

std::string ReplyDialect::unknown_command(std::string_view code) const {
  return fmt::format("echo:Unknown command: \"{}\"", code);
}

std::string ReplyDialect::not_homed(double, double, double, double) const {
  return "echo:Home XYZ First";
}

std::vector<std::string> ReplyDialect::refused_while_shut_down(std::string_view why) const {
  return {fmt::format("Error:{}", why)};
}

std::string ReplyDialect::temperatures(const Temperatures& t, bool heating) const {
  std::string report = fmt::format("T:{:.2f} /{:.2f} B:{:.2f} /{:.2f} @:{} B@:{}", t.hotend, t.hotend_target, t.bed,
                                   t.bed_target, t.hotend < t.hotend_target ? 127 : 0, t.bed < t.bed_target ? 127 : 0);
  if (heating) report += " W:?";
  return report;
}

std::string ReplyDialect::temperature_ok(const Temperatures& t) const {
  return fmt::format("ok {}", temperatures(t, false));
}

std::string ReplyDialect::position(double x, double y, double z, double e, long count_x, long count_y,
                                   long count_z) const {
  return fmt::format("X:{:.2f} Y:{:.2f} Z:{:.2f} E:{:.2f} Count X:{} Y:{} Z:{}", x, y, z, e, count_x, count_y,
                     count_z);
}

std::string ReplyDialect::link_report(const VirtualPrinterConfig& config) {
  return config.report_link ? fmt::format(" TIME_SCALE:{} BAUD:{}", config.time_scale, config.baud) : std::string();
}

std::vector<std::string> ReplyDialect::firmware_report(const VirtualPrinterConfig& config) const {
  return {
      fmt::format("FIRMWARE_NAME:Marlin {} (gc-virtual-printer) SOURCE_CODE_URL:github.com/MarlinFirmware/Marlin "
                  "PROTOCOL_VERSION:1.0 MACHINE_TYPE:Virtual EXTRUDER_COUNT:1{}",
                  firmware_version(), link_report(config)),
      "Cap:SERIAL_XON_XOFF:0",
      fmt::format("Cap:ADVANCED_OK:{}", config.advanced_ok ? 1 : 0),
      "Cap:EMERGENCY_PARSER:1",
      "Cap:AUTOREPORT_TEMP:1",
      "Cap:AUTOREPORT_POS:0",
      "Cap:HOST_ACTION_COMMANDS:1",
      // Not a Marlin capability (Marlin does not report its MAX_CMD_SIZE);
      // a host that reads it can size its lines.
      fmt::format("Cap:MAX_CMD_SIZE:{}", config.max_line),
  };
}

namespace {

class MarlinDialect final : public ReplyDialect {};

// Marlin 1.1 speaks as Marlin 2 on the serial line (the same messages,
// ADVANCED_OK, busy keepalive); only its version differs.
class Marlin1Dialect final : public ReplyDialect {
 public:
  const FirmwareFlavor& firmware() const override { return marlin1_firmware(); }
  std::string_view firmware_version() const override { return "1.1.9"; }
};

}  // namespace

const ReplyDialect& marlin_dialect() {
  static const MarlinDialect dialect;
  return dialect;
}

const ReplyDialect& marlin1_dialect() {
  static const Marlin1Dialect dialect;
  return dialect;
}

std::span<const ReplyDialect* const> dialects() {
  static const ReplyDialect* const kAll[] = {&marlin_dialect(), &marlin1_dialect(), &klipper_dialect(),
                                             &prusa_dialect(), &rrf_dialect()};
  return kAll;
}

const ReplyDialect* find_dialect(std::string_view name) {
  const FirmwareFlavor* firmware = find_firmware(name);
  for (const ReplyDialect* d : dialects())
    if (firmware != nullptr && &d->firmware() == firmware) return d;
  return nullptr;
}

}  // namespace gcode::serial
