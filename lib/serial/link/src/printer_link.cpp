#include "gcode/serial/link/printer_link.hpp"

#include <unistd.h>

#include <utility>

namespace gcode::serial {

PortLink::PortLink(std::string path, const PortOptions& options, int fd)
    : PrinterLink(fd, options.baud, 1, is_pseudo_terminal(fd)), path_(std::move(path)), options_(options) {}

PortLink::~PortLink() {
  if (fd_ >= 0) ::close(fd_);
}

void PortLink::reopen(double seconds) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  // No DTR pulse again: the board came back by itself.
  fd_ = wait_for_port(path_, PortOptions{options_.baud, false}, seconds);
}

}  // namespace gcode::serial
