// gc-send: stream G-code to a printer over a serial port (or to the built-in
// virtual printer), keeping the printer's buffers full without overrunning
// them, and take pause/resume requests from a control FIFO while it prints.
// The options are cli/send_options.hpp; the work is lib/serial
// (send_job.hpp, send_session.hpp, print_control.hpp).
#include <cstdio>

#include "gcode/cli/send_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/serial/control/control_verbs.hpp"
#include "gcode/serial/job/send_job.hpp"
#include "gcode/serial/link/port.hpp"
#include "gcode/transform/custom_gcode.hpp"

namespace {

int list_ports() {
  auto ports = gcode::serial::list_serial_ports();
  for (const auto& p : ports) std::printf("%s\t%s\n", p.path.c_str(), p.description.c_str());
  if (ports.empty()) std::fprintf(stderr, "gc-send: no serial ports found (--port virtual needs none)\n");
  return 0;
}

// The exit statuses the man page lists: 130 after an emergency stop (M112),
// 1 a failure or a refused resume.
int exit_status(const gcode::serial::SendOutcome& outcome) {
  using gcode::serial::SendEnd;
  switch (outcome.end) {
    case SendEnd::Finished:
    case SendEnd::AlreadyFinished: return 0;
    case SendEnd::EmergencyStop: return 130;
    case SendEnd::Failed:
    case SendEnd::Refused: return 1;
  }
  return 1;
}

int run(gcode::cli::SendOptions& o) {
  gcode::serial::SendJob& job = o.job;
  gcode::cli::load_pause_texts(o.pause);
  job.control.pause = o.pause.config;
  if (!o.cancel_gcode.empty()) job.control.cancel_gcode = gcode::load_custom_gcode(o.cancel_gcode);
  gcode::Diagnostics diag("gc-send", job.quiet ? -1 : job.verbose);
  return exit_status(gcode::serial::run_send_job(job, diag));
}

}  // namespace

int main(int argc, char** argv) {
  gcode::cli::SendOptions o;
  o.pause.config.message = "Paused at layer {layer}";  // gc-pause-at's default
  gcode::cli::Tool tool(
      "gc-send",
      "gc-send: stream G-code to a printer over a serial port, keeping its buffers full without overrunning\n"
      "them, and pause, resume, speed up or cancel the print from a control FIFO while it runs:\n"
      "  echo pause > $XDG_RUNTIME_DIR/gc-send/ttyACM0.fifo     (finish the layer rushed, then park)\n"
      "  echo resume > $XDG_RUNTIME_DIR/gc-send/ttyACM0.fifo    (return exactly and go on)\n"
      "Control commands, one a line:\n" +
          gcode::serial::control_verbs_help() +
          "Comments and blank lines are not sent; @pause, ;@pause and --pause-on codes pause the host. Every\n"
      "line is numbered and checksummed, resent on request, and the end waits for M400. Ctrl-C cancels\n"
      "(retract, lift, park, heaters off); Ctrl-C twice sends M112. The default port is the virtual printer:\n"
      "  gc-subdivide --max 0.2 part.gcode | gc-send --port /dev/ttyACM0 --baud 250000\n"
      "  gc-send --port virtual:time-scale=20 examples/cube.gcode");
  gcode::cli::add_send_options(tool, o);
  tool.check([&] { gcode::cli::resolve_send_options(tool, o); });
  return tool.run(argc, argv, [&] { return o.list_ports ? list_ports() : run(o); });
}
