#pragma once
// gc-send's pipeline in one event loop: G-code from the input runs through
// the library's pipeline (pipeline.hpp: lines, state, layers, and any stages
// a caller adds), whose last stage strips comments and hands commands to the
// Sender; the Sender's bytes go to the port, the port's lines back to the
// Sender. Ctrl-C once stops sending and waits for the lines in flight;
// Ctrl-C twice sends M112 at once.
#include <signal.h>

#include <cstdint>
#include <string>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/layer_marker.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/serial/event_loop.hpp"
#include "gcode/serial/sender.hpp"

namespace gcode::serial {

class SendSession : private Stage {
 public:
  // Does not own the descriptors. `port_fd` is made non-blocking.
  SendSession(EventLoop& loop, Sender& sender, int input_fd, int port_fd, Diagnostics& diagnostics);
  ~SendSession() override;
  SendSession(const SendSession&) = delete;
  SendSession& operator=(const SendSession&) = delete;

  // Runs until the sender is finished.
  void run();
  std::uint64_t host_commands() const { return host_commands_; }
  std::uint64_t input_lines() const { return input_lines_; }
  int layers() const { return pipeline_.tracker().layer_count(); }

 private:
  // The last stage: what reaches it is sent.
  void line(const TrackedLine& t, Emitter& out) override;
  bool reads_state() const override { return false; }
  void read_input();
  void read_port();
  void flush_port();
  void on_signal();
  void update();

  EventLoop& loop_;
  Sender& sender_;
  int input_fd_;
  int port_fd_;
  int signal_fd_ = -1;
  sigset_t saved_mask_{};  // the signal mask before the session blocked SIGINT and SIGTERM
  Diagnostics& diag_;
  LayerMarkers markers_;
  Pipeline pipeline_;
  std::uint64_t input_lines_ = 0;
  std::uint64_t host_commands_ = 0;
  bool input_done_ = false;
  std::string port_in_;       // a partial line from the printer
  std::string scratch_;       // a command rebuilt without its paren comments
  int input_watch_ = -1;
  int port_watch_ = -1;
  int interrupts_ = 0;
};

}  // namespace gcode::serial
