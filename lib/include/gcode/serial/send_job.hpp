#pragma once
// One run of gc-send, from its settled options: the port (a device, a pty,
// or the in-process virtual printer), the sender, the session with its
// control FIFO and progress, and the summary at the end. Returns the exit
// status: 0 done (a cancel the printer confirmed included), 1 failed, 130
// after an emergency stop.
#include <functional>
#include <string>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/e_mode.hpp"
#include "gcode/core/print_area.hpp"
#include "gcode/serial/print_control.hpp"
#include "gcode/serial/progress.hpp"
#include "gcode/serial/sender.hpp"
#include "gcode/serial/virtual_printer.hpp"

namespace gcode::serial {

struct SendJob {
  std::string file;                 // "" or "-": standard input
  std::string layer_marker;         // RE2 pattern of a layer start ("": the slicers' markers)
  EModeChoice e_mode = EModeChoice::Auto;  // a file that never says M82/M83
  std::string port = "virtual";     // a path, or virtual[:opts] (vconfig holds them)
  int baud = 250000;
  bool reset = false;
  double reconnect = 180;           // seconds a lost port is waited for (0: the print ends at once)
  SenderConfig sender;              // flow, queue, buffers, timeouts, line limits, pace
  VirtualPrinterConfig vconfig;
  PrintControlConfig control;       // park filled in by `park` once the file's area is known
  std::function<ParkRules(const PrintArea&, PauseConfig&)> park;
  std::string control_path;         // "" = none
  ProgressOptions progress;
  std::string log_path;             // every line both ways with timestamps
  std::string journal_path;         // "" = no journal (--no-journal)
  bool resume = false;              // --resume: go on with the print journal_path holds
  bool quiet = false;
  int verbose = 0;
};

bool is_virtual_port(const std::string& port);
int run_send_job(SendJob& job, Diagnostics& diagnostics);

}  // namespace gcode::serial
