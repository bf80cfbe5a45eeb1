#pragma once
// One run of gc-send, from its settled options: the printer at the far end
// (link/printer_link.hpp: a device or pty, or the simulated printer the
// front end chose), the sender, the session with its
// control FIFO and progress, and the summary at the end. Messages go out
// through the Diagnostics the tool gives; the run says how it ended as a
// value, and the tool makes an exit status of it.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/e_mode.hpp"
#include "gcode/core/print_area.hpp"
#include "gcode/serial/control/print_control.hpp"
#include "gcode/serial/job/progress.hpp"
#include "gcode/serial/link/event_loop.hpp"
#include "gcode/serial/link/printer_link.hpp"
#include "gcode/serial/sender/sender.hpp"

namespace gcode::serial {

// Makes the far end of the line; `wait`: seconds a port that is away is
// waited for (a resume started while the USB link is still down).
using MakePrinterLink = std::function<std::unique_ptr<PrinterLink>(EventLoop&, double wait, Diagnostics&)>;

struct SendJob {
  std::string file;                 // "" or "-": standard input
  std::string layer_marker;         // RE2 pattern of a layer start ("": the slicers' markers)
  EModeChoice e_mode = EModeChoice::Auto;  // a file that never says M82/M83
  std::string port = "virtual";     // a path, or virtual[:opts]: the journal's name of the printer
  int baud = 250000;
  bool reset = false;
  double reconnect = 180;           // seconds a lost port is waited for (0: the print ends at once)
  SenderConfig sender;              // flow, queue, buffers, timeouts, line limits, pace
  MakePrinterLink link;             // empty: the device or pty at `port` (PortLink)
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

// How a run ended.
enum class SendEnd : std::uint8_t {
  Finished,         // the printer took every line (a cancel it confirmed included)
  AlreadyFinished,  // a resume found the print ended: nothing sent, the journal closed
  EmergencyStop,    // cancelled with M112 (a second Ctrl-C): no safe end
  Failed,           // `reason` says why (reported already)
  Refused,          // a resume refused before anything was sent: `reason` says why (reported already)
};

struct SendOutcome {
  SendEnd end = SendEnd::Finished;
  std::string reason;  // Failed: the sender's failure; Refused: the refusal
};

SendOutcome run_send_job(SendJob& job, Diagnostics& diagnostics);

}  // namespace gcode::serial
