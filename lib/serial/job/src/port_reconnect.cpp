#include "gcode/serial/job/port_reconnect.hpp"

#include <limits>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

namespace gcode::serial {

PortReconnect::PortReconnect(Sender& sender, Diagnostics& diagnostics, std::string path, PortOptions options,
                             double seconds)
    : sender_(sender), diag_(diagnostics), path_(std::move(path)), options_(options), seconds_(seconds) {
  options_.reset = false;
}

bool PortReconnect::lost(std::string_view why, double now) {
  if (path_.empty() || seconds_ <= 0 || sender_.finished()) {
    sender_.disconnected(why);
    return false;
  }
  lost_at_ = now;
  next_try_ = lost_at_ + kRetry;
  waiting_ = true;
  sender_.link_lost(lost_at_);
  diag_.warn(0, fmt::format("lost the printer's port ({}) after {}; waiting up to {:g} s for {} to come back "
                            "(--reconnect)",
                            why, sender_.describe(sender_.last_acknowledged()), seconds_, path_));
  return true;
}

double PortReconnect::next_try() const {
  return waiting_ ? next_try_ : std::numeric_limits<double>::infinity();
}

int PortReconnect::attempt(double now) {
  if (!waiting_) return -1;
  int fd = -1;
  try {
    fd = open_serial_port(path_, options_);
  } catch (const std::runtime_error&) {
    fd = -1;  // not back yet
  }
  if (fd < 0) {
    if (now - lost_at_ < seconds_) {
      next_try_ = now + kRetry;
      return -1;
    }
    give_up(fmt::format("the port {} did not come back within {:g} s (--reconnect)", path_, seconds_));
    return -1;
  }
  waiting_ = false;
  diag_.warn(0, fmt::format("the port is back after {:.2f} s; asking the printer where it is", now - lost_at_));
  sender_.link_back(now);
  return fd;
}

void PortReconnect::give_up(std::string_view why) {
  waiting_ = false;
  sender_.disconnected(why);
}

}  // namespace gcode::serial
