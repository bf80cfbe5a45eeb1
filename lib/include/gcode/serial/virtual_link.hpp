#pragma once
// Puts a VirtualPrinter at the far end of a file descriptor (one end of a
// socketpair for `gc-send --port virtual`, a pty master for
// gc-virtual-printer) and drives it from an event loop, mapping wall time to
// simulated time with the model's time scale.
#include <string>

#include "gcode/serial/event_loop.hpp"
#include "gcode/serial/virtual_printer.hpp"

namespace gcode::serial {

class VirtualLink {
 public:
  // Does not own `fd` or `printer`; `fd` is made non-blocking.
  VirtualLink(EventLoop& loop, VirtualPrinter& printer, int fd);

  // Simulated seconds since the link started.
  double simulated_now() const;
  // The model dropped the link (disconnect fault): the descriptor should be closed.
  bool closed() const { return closed_; }
  void set_on_close(std::function<void()> f) { on_close_ = std::move(f); }

 private:
  void pump();
  void on_io(short revents);

  EventLoop& loop_;
  VirtualPrinter& printer_;
  int fd_;
  int watch_ = -1;
  bool socket_ = false;  // a socketpair (gc-send --port virtual), else a pty master
  double wall0_;
  double scale_;
  std::string out_;  // transmitted by the model, not yet accepted by the fd
  bool closed_ = false;
  std::function<void()> on_close_;
};

}  // namespace gcode::serial
