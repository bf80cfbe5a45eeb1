#include "gcode/serial/virtual_dialect.hpp"

#include <fmt/format.h>

#include "gcode/serial/virtual_printer_options.hpp"

namespace gcode::serial {

namespace {

class MarlinDialect final : public ReplyDialect {
 public:
  std::string greeting() const override { return "start"; }

  std::vector<std::string> restart_greeting(GreetingForm form) const override {
    switch (form) {
      // A USB-serial chip often hands over a NUL (line noise of the reset) first.
      case GreetingForm::NulStart: return {std::string("\0start", 6)};
      case GreetingForm::Twice: return {"start", "start"};
      case GreetingForm::ExternalReset:
        return {"start", "echo: External Reset", "Marlin 2.1.2 (gc-virtual-printer)"};
      case GreetingForm::Start: break;
    }
    return {"start"};
  }

  std::string ok(long long number, bool advanced, int planner_free, int queue_free) const override {
    if (!advanced) return "ok";
    if (number >= 0) return fmt::format("ok N{} P{} B{}", number, planner_free, queue_free);
    return fmt::format("ok P{} B{}", planner_free, queue_free);
  }

  std::vector<std::string> rejected(LineFault fault, long long last_line) const override {
    const char* message = "";
    switch (fault) {
      case LineFault::LineNumber: message = "Line Number is not Last Line Number+1, Last Line: "; break;
      case LineFault::NoChecksum: message = "No Checksum with line number, Last Line: "; break;
      case LineFault::Checksum: message = "checksum mismatch, Last Line: "; break;
      case LineFault::NoLineNumber: message = "No Line Number with checksum, Last Line: "; break;
    }
    return {fmt::format("Error:{}{}", message, last_line), fmt::format("Resend: {}", last_line + 1), "ok"};
  }

  std::string busy() const override { return "echo:busy: processing"; }

  std::string unknown_command(std::string_view code) const override {
    return fmt::format("echo:Unknown command: \"{}\"", code);
  }

  std::string temperatures(const Temperatures& t, bool heating) const override {
    std::string report = fmt::format("T:{:.2f} /{:.2f} B:{:.2f} /{:.2f} @:{} B@:{}", t.hotend, t.hotend_target, t.bed,
                                     t.bed_target, t.hotend < t.hotend_target ? 127 : 0, t.bed < t.bed_target ? 127 : 0);
    if (heating) report += " W:?";
    return report;
  }

  std::string temperature_ok(const Temperatures& t) const override {
    return fmt::format("ok {}", temperatures(t, false));
  }

  std::string position(double x, double y, double z, double e, long count_x, long count_y,
                       long count_z) const override {
    return fmt::format("X:{:.2f} Y:{:.2f} Z:{:.2f} E:{:.2f} Count X:{} Y:{} Z:{}", x, y, z, e, count_x, count_y,
                       count_z);
  }

  std::vector<std::string> firmware_report(const VirtualPrinterConfig& config) const override {
    std::string link = config.report_link ? fmt::format(" TIME_SCALE:{} BAUD:{}", config.time_scale, config.baud)
                                          : std::string();
    return {
        fmt::format("FIRMWARE_NAME:Marlin 2.1.2 (gc-virtual-printer) SOURCE_CODE_URL:github.com/MarlinFirmware/Marlin "
                    "PROTOCOL_VERSION:1.0 MACHINE_TYPE:Virtual EXTRUDER_COUNT:1{}",
                    link),
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

  std::string halted() const override { return "Error:Printer halted. kill() called!"; }
  std::string thermal_runaway() const override { return "Error:Thermal Runaway, system stopped! Heater_ID: 0"; }
};

}  // namespace

const ReplyDialect& marlin_dialect() {
  static const MarlinDialect dialect;
  return dialect;
}

}  // namespace gcode::serial
