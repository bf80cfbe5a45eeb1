#pragma once
// gc-send's options: FILE, --layer-marker and --e-mode as every tool that
// reads G-code takes them (tool.hpp), then in groups: the link (port, baud, flow control, the
// firmware's buffers, timeouts, line limits), control (the FIFO, the rush
// of a pause, in-stream pauses, cancel), progress, and the pause block's
// options shared with gc-pause-at (pause_options.hpp).
#include <string>

#include "gcode/cli/pause_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/serial/job/send_job.hpp"
#include "gcode/serial/sim/virtual_printer.hpp"

namespace gcode::cli {

struct SendOptions {
  serial::SendJob job;
  serial::VirtualPrinterConfig vconfig;  // --port virtual[:OPTIONS]: the simulated printer job.link makes
  FilterOptions io;         // FILE, --layer-marker, --e-mode: read as every tool reads G-code
  PauseOptions pause;
  std::string flow = "auto";
  int queue = 4, rx_buffer = 128, max_timeouts = 5;
  int max_line = 96;
  double timeout = 10;
  std::string control;      // --control PATH
  bool no_control = false;
  std::string journal;      // --journal PATH
  bool no_journal = false;
  std::string resume;       // --resume [JOURNAL]
  std::string pause_on;     // M0,M1,...
  std::string cancel_gcode;
  std::string exclude;      // --exclude ID[,ID...]
  bool no_pace = false;
  bool list_ports = false;
  bool delta = false;       // --delta: no resume after a reset
  double interval = 5;
};

void add_send_options(Tool& tool, SendOptions& options);
// After parsing: checks (UsageError) and fills options.job.
void resolve_send_options(Tool& tool, SendOptions& options);

}  // namespace gcode::cli
