#pragma once
// gc-send --reconnect: a port that fails mid-print (EIO or ENODEV from an
// unplugged USB cable, a hang-up) is not the end of it. The same path is
// waited for (a /dev/serial/by-id name survives a replug) and opened again
// without a DTR reset (a pulse would restart the board and lose the print);
// then the sender finds out where the printer is (Sender::link_back). The
// session's loop runs meanwhile: the control FIFO answers, the status file
// says "reconnecting", Ctrl-C ends it. Its times are the caller's clock.
#include <string>
#include <string_view>

#include "gcode/core/diagnostics.hpp"
#include "gcode/serial/link/port.hpp"
#include "gcode/serial/sender/sender.hpp"

namespace gcode::serial {

class PortReconnect {
 public:
  static constexpr double kRetry = 0.1;  // seconds between attempts to open the port

  // `path` waited for up to `seconds` (0: a lost port ends the print).
  PortReconnect(Sender& sender, Diagnostics& diagnostics, std::string path, PortOptions options, double seconds);

  // The port was lost (`why`): true when it is waited for (the caller
  // closes its descriptor at once: a USB device whose old node is still held
  // open comes back under another name, ttyACM1 for ttyACM0); false when
  // the print ended (Sender::disconnected).
  bool lost(std::string_view why, double now);
  bool waiting() const { return waiting_; }
  // When to try again (infinity while not waiting).
  double next_try() const;
  // One attempt to open the port: its new descriptor once it is back (the
  // sender told), else -1 (not back yet, or past the time given: the
  // print ended, waiting() is false).
  int attempt(double now);
  // Nobody to wait for any more (Ctrl-C, a cancel): `why` ends the print.
  void give_up(std::string_view why);

 private:
  Sender& sender_;
  Diagnostics& diag_;
  std::string path_;
  PortOptions options_;
  double seconds_;
  bool waiting_ = false;
  double lost_at_ = 0;
  double next_try_ = 0;
};

}  // namespace gcode::serial
