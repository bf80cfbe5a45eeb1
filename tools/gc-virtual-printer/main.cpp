// gc-virtual-printer: the Marlin model of gc-send's built-in virtual printer,
// on a pseudo-terminal, so that any host (gc-send, printcore, OctoPrint) can
// connect to it like a USB printer.
#include "gcode/cli/tool.hpp"
#include "gcode/cli/virtual_printer_options.hpp"
#include "gcode/serial/sim/virtual_printer_runner.hpp"

int main(int argc, char** argv) {
  gcode::cli::VirtualPrinterToolOptions o;
  gcode::cli::Tool tool(
      "gc-virtual-printer",
      "gc-virtual-printer: a simulated printer (Marlin, Klipper, Prusa or RepRapFirmware) on a pseudo-terminal. PATH becomes a symlink to the\n"
      "pty; connect any host to it. It models the link's byte rate, the RX buffer (overruns lose bytes), the\n"
      "command queue, the planner, heating, Marlin's checksum/line-number errors and Resend replies, and can\n"
      "inject faults. Runs until interrupted:\n"
      "  gc-virtual-printer --link /tmp/printer --time-scale 20 & gc-send --port /tmp/printer part.gcode");
  gcode::cli::add_virtual_printer_options(tool, o);
  return tool.run(argc, argv, [&] { return gcode::serial::run_virtual_printer(o.run, o.config); });
}
