#pragma once
// gc-virtual-printer's options and what they map to
// (serial/virtual_printer_runner.hpp's VirtualPrinterRun, the printer's
// VirtualPrinterConfig): the pty's link, the firmware and its sizes, time,
// faults, the greeting after a reset, the log.
#include <string>
#include <vector>

#include "gcode/cli/tool.hpp"
#include "gcode/serial/sim/virtual_fault.hpp"
#include "gcode/serial/sim/virtual_printer_options.hpp"
#include "gcode/serial/sim/virtual_printer_runner.hpp"

namespace gcode::cli {

struct VirtualPrinterToolOptions {
  serial::VirtualPrinterRun run;
  serial::VirtualPrinterConfig config;
  std::vector<std::string> faults;   // --fault KEY=VALUE, repeatable
  std::string greeting = "start";    // --greeting FORM
  bool no_resend_ok = false, no_link_report = false;
  bool octoprint = false;  // OctoPrint's virtual printer's defaults
};

// Every option, and the check that settles the config (faults and greeting
// parsed, sizes and times sensible: a usage error otherwise).
void add_virtual_printer_options(Tool& tool, VirtualPrinterToolOptions& options);

}  // namespace gcode::cli
