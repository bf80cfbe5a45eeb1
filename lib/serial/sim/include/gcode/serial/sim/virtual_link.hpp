#pragma once
// Puts a VirtualPrinter at the far end of a file descriptor (one end of a
// socketpair for `gc-send --port virtual`, a pty master for
// gc-virtual-printer) and drives it from an event loop, mapping wall time to
// simulated time with the model's time scale.
#include <string>

#include "gcode/serial/link/event_loop.hpp"
#include "gcode/serial/sim/virtual_printer.hpp"

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
  // A link drop (virtual_fault.hpp): `on_drop` is called when the model's
  // link goes down (the descriptor is no longer used: close it, remove its
  // path), `on_restore` when it comes back and returns the new descriptor.
  // Without them the descriptor stays and the link is silent while down.
  void set_on_drop(std::function<void()> on_drop, std::function<int()> on_restore) {
    on_drop_ = std::move(on_drop);
    on_restore_ = std::move(on_restore);
  }
  // Fires a fault now (gc-virtual-printer's signals): the model is brought
  // up to now first.
  void reset_printer();
  void drop_link(double seconds, bool reset_after);

 private:
  void pump();
  void on_io(short revents);
  void follow_link_state();

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
  bool down_ = false;
  std::function<void()> on_drop_;
  std::function<int()> on_restore_;
};

}  // namespace gcode::serial
