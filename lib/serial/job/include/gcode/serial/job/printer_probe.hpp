#pragma once
// Before a resume sends anything of the print (gc-send --resume), ask the
// printer what it did with the lines it took (resume_plan.hpp): the line it
// expects next, from its answer to a line sent with a deliberately wrong
// number ("Error:Line Number is not Last Line Number+1, Last Line: 1234"),
// where it stands once the moves it took have run (M400, then M114), and
// whether it greeted (reset) meanwhile. None of it moves the printer: a
// refused line is not run, M400 waits for what it took, M105 and M114 only
// report. A blocking exchange on the port before the event loop starts.
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "gcode/serial/journal/resume_plan.hpp"

namespace gcode::serial {

struct ProbeResult {
  PrinterFindings findings;
  bool answered = false;      // it named the line it took last
  long long last_line = -1;   // that line (0: its numbering is back at the start)
  bool greeted = false;       // it said "start" (it reset)
  std::string problem;        // why the printer cannot be trusted ("" none)
};

// The port went away during the exchange (a USB drop): asked again once it
// is back, the printer answers for what it did meanwhile.
struct PortLost : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `timeout`: seconds for each answer (a printer draining a full queue of
// slow moves answers late). `trace` sees every line both ways. Throws
// PortLost when the port closes or fails.
ProbeResult probe_printer(int fd, double timeout, const std::function<void(std::string_view)>& trace);

}  // namespace gcode::serial
