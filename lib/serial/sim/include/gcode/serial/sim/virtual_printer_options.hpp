#pragma once
// What the virtual printer (virtual_printer.hpp) is: its buffers, link,
// planner and faults, as `virtual:key=value,...` names them (gc-send
// --port virtual:..., gc-virtual-printer).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/serial/sim/virtual_fault.hpp"

namespace gcode::serial {

struct VirtualPrinterConfig {
  // Whose replies and quirks: a name of core/firmware.hpp's firmwares()
  // (virtual_dialect.hpp plays each).
  std::string firmware = "marlin2";
  // How long the user at the printer takes to answer a wait that asks for
  // them (Prusa's M600, its own pause, "M115 U" newer), in simulated seconds.
  double user_seconds = 5;
  double baud = 250000;
  int queue = 4;              // BUFSIZE
  int rx_buffer = 128;        // RX_BUFFER_SIZE
  // > 0: a byte that meets a full receive buffer is not lost: the write
  // waits for room, for at most this many simulated seconds, and then the
  // rest of it is dropped (OctoPrint's virtual printer: its 64-byte buffer
  // blocks the writer until its write timeout). 0: lost at once (a UART).
  double write_timeout = 0;
  // OctoPrint's virtual printer's scripted errors, once each: line 100 is
  // refused (a resend), 105 refused with its ok lost, 110 taken as having
  // no line number, 115 as a checksum mismatch.
  bool scripted_errors = false;
  int max_line = 96;          // MAX_CMD_SIZE: a line keeps max_line - 1 bytes
  int planner = 16;           // BLOCK_BUFFER_SIZE
  double time_scale = 1;      // simulated seconds per wall second
  // Moves run this many times faster than the file's feed rates say, and
  // M115 does not tell: a speed knob at 125 %, M220 from elsewhere, firmware
  // limits above the host's model. time_scale is known to the host; this is not.
  double speed_factor = 1;
  bool advanced_ok = false;   // answer "ok N.. P.. B.."
  bool resend_ok = true;      // an "ok" follows "Resend: n" (Marlin's does; some firmwares send none)
  double idle_wait = 0;       // "wait" every this many seconds while idle (Marlin's NO_TIMEOUTS), 0: never
  bool instant_moves = false; // moves take no time: the link is the only limit
  // gc-send's clock is the simulation's (EventLoop::use_simulated_clock)
  // when >= 0: each time gc-send wakes it takes this many seconds (its
  // latency, as a quiet host's), and nothing else of the host counts, so a
  // run's figures are the same on a loaded machine (tests that judge pacing
  // on them). In-process printer only. "simulated-clock" alone: 50 us.
  double simulated_clock = -1;
  static constexpr double kHostLatency = 50e-6;
  bool report_link = true;    // M115 names TIME_SCALE and BAUD (a real firmware does not)
  double heat_rate = 10;      // degrees per second (the bed heats at a third of it)
  // Faults: probabilities per received line / per answer.
  double corrupt = 0;         // a received line gets one byte changed
  double drop_ok = 0;         // an "ok" is not sent
  double resend = 0;          // a good line is rejected as if corrupted
  double garbage = 0;         // a line of junk after an answer
  double busy = 0;            // a command stalls 3 s with busy messages
  long long silent_after = -1;     // stop answering after this many commands
  long long halt_after = -1;       // report a fatal error after this many commands
  long long disconnect_after = -1; // drop the link after this many commands
  bool home_fails = false;         // every G28 fails: an endstop that never triggers
  long long unhome_after = -1;     // forget the homing after this many commands (motors switched off)
  std::vector<ScheduledFault> scheduled;      // resets and link drops at chosen moments
  GreetingForm greeting = GreetingForm::Start; // how a reset board greets
  std::uint32_t seed = 1;
  std::string log_path;       // where the caller writes the executed-command log
};

// Applies "key=value,key=value" (the part after "virtual:") to `config`.
// Keys: firmware user-seconds resend-ok idle-wait baud queue rx write-timeout scripted-errors octoprint (rx=64,
// write-timeout=10, scripted-errors, instant-moves: OctoPrint's virtual printer's defaults) max-line planner
// time-scale speed-factor advanced-ok instant-moves simulated-clock
// report-link heat-rate corrupt drop-ok resend garbage busy silent-after
// halt-after disconnect-after home-fails unhome-after seed log greeting, and scheduled faults
// (virtual_fault.hpp: "reset@line=N", "drop=S@time=T"). Throws std::invalid_argument naming a bad key or value.
void parse_virtual_options(std::string_view text, VirtualPrinterConfig& config);

}  // namespace gcode::serial
