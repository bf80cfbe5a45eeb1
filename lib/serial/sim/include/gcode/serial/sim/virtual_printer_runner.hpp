#pragma once
// gc-virtual-printer's run: the Marlin model (virtual_printer.hpp) on a
// pseudo-terminal whose slave a symlink names, driven by an event loop
// (virtual_link.hpp) until SIGINT, SIGTERM or SIGHUP, or until the model
// drops the link (a disconnect fault). Any host can connect to the symlink
// like a USB printer. A link drop (virtual_fault.hpp) closes the pty and
// removes the symlink; when the link returns a new pty appears at the same
// path. SIGUSR1 resets the printer now, SIGUSR2 drops the link now for
// `drop_seconds`, so a test can fire a fault at the moment it chooses.
#include <string>

#include "gcode/serial/sim/virtual_printer.hpp"

namespace gcode::serial {

struct VirtualPrinterRun {
  std::string link;  // the symlink to create for the pseudo-terminal
  std::string log;   // "" or a file for every executed command (VirtualPrinter's log)
  bool quiet = false;  // no start line and no statistics on standard error
  std::string name = "gc-virtual-printer";  // the prefix of the messages
  double drop_seconds = 5;  // simulated seconds of a SIGUSR2 link drop
};

// The statistics line printed at the end: "executed N, accepted lines N, ...".
std::string virtual_printer_summary(const VirtualPrinter& printer, bool link_dropped);

// Runs the printer until a signal or a dropped link; returns the exit
// status (0). Throws std::runtime_error when the log or the pty cannot be made.
int run_virtual_printer(const VirtualPrinterRun& run, const VirtualPrinterConfig& config);

}  // namespace gcode::serial
