// gc-send --reconnect: a port that fails mid-print (EIO or ENODEV from an
// unplugged USB cable, a hang-up) is not the end of it. The session waits
// for the same path to come back (a /dev/serial/by-id name survives a
// replug), opens it again without a DTR reset, and the sender finds out
// where the printer is (sender_relink.cpp). While it waits the loop runs:
// the control FIFO answers, the status file says "reconnecting", Ctrl-C
// ends it.
#include <poll.h>
#include <unistd.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/serial/job/send_session.hpp"

namespace gcode::serial {

namespace {
constexpr double kRetry = 0.1;  // seconds between attempts to open the port
}  // namespace

void SendSession::set_reconnect(const std::string& path, const PortOptions& options, double seconds) {
  reconnect_path_ = path;
  reconnect_options_ = options;
  reconnect_options_.reset = false;  // a DTR pulse would restart the board and lose the print
  reconnect_seconds_ = seconds;
  loop_.add_timer([this] { return reconnecting_ ? next_try_ : std::numeric_limits<double>::infinity(); },
                  [this](double now) {
                    try_reconnect(now);
                    update();
                  });
}

std::string_view SendSession::state_label() const {
  if (sender_.state() == SenderState::Failed) return "failed";
  if (sender_.emergency()) return "stopped";
  if (sender_.finished()) return "done";
  if (reconnecting_) return "reconnecting";
  return control_->state_label();
}

void SendSession::port_lost(std::string_view why) {
  if (port_watch_ >= 0) {
    loop_.set_events(port_watch_, 0);
    loop_.remove_fd(port_watch_);
    port_watch_ = -1;
  }
  if (reconnect_path_.empty() || reconnect_seconds_ <= 0 || sender_.finished()) {
    sender_.disconnected(why);
    return;
  }
  // Closed at once: a USB device whose old node is still held open comes
  // back under another name (ttyACM1 for ttyACM0).
  ::close(port_fd_);
  port_fd_ = -1;
  port_replaced_ = true;
  lost_at_ = EventLoop::now();
  next_try_ = lost_at_ + kRetry;
  reconnecting_ = true;
  sender_.link_lost(lost_at_);
  port_in_.clear();
  diag_.warn(0, fmt::format("lost the printer's port ({}) after {}; waiting up to {:g} s for {} to come back "
                            "(--reconnect)",
                            why, sender_.describe(sender_.last_acknowledged()), reconnect_seconds_, reconnect_path_));
}

void SendSession::try_reconnect(double now) {
  if (!reconnecting_) return;
  int fd = -1;
  try {
    fd = open_serial_port(reconnect_path_, reconnect_options_);
  } catch (const std::runtime_error&) {
    fd = -1;  // not back yet
  }
  if (fd < 0) {
    if (now - lost_at_ < reconnect_seconds_) {
      next_try_ = now + kRetry;
      return;
    }
    reconnecting_ = false;
    sender_.disconnected(fmt::format("the port {} did not come back within {:g} s (--reconnect)", reconnect_path_,
                                     reconnect_seconds_));
    return;
  }
  reconnecting_ = false;
  port_fd_ = fd;
  watch_port();
  diag_.warn(0, fmt::format("the port is back after {:.2f} s; asking the printer where it is", now - lost_at_));
  sender_.link_back(now);
}

}  // namespace gcode::serial
