#include "gcode/serial/sim/virtual_printer_link.hpp"

#include <sys/socket.h>
#include <unistd.h>

#include <stdexcept>

#include <fmt/format.h>

namespace gcode::serial {

namespace {
constexpr std::string_view kVirtual = "virtual";
}  // namespace

bool is_virtual_port(const std::string& port) {
  return port == kVirtual || port.rfind(std::string(kVirtual) + ":", 0) == 0;
}

VirtualPrinterLink::VirtualPrinterLink(EventLoop& loop, const VirtualPrinterConfig& config)
    : PrinterLink(-1, config.baud, config.time_scale, false) {
  int fds[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
    throw std::runtime_error("cannot create the virtual printer's link");
  fd_ = fds[0];
  model_fd_ = fds[1];
  try {
    if (!config.log_path.empty()) {
      log_ = std::fopen(config.log_path.c_str(), "w");
      if (log_ == nullptr) throw std::runtime_error(fmt::format("cannot write {}", config.log_path));
    }
    printer_ = std::make_unique<VirtualPrinter>(config, log_);
    if (config.simulated_clock >= 0) EventLoop::use_simulated_clock(config.simulated_clock);
    link_ = std::make_unique<VirtualLink>(loop, *printer_, model_fd_);
  } catch (...) {
    ::close(model_fd_);
    ::close(fd_);
    throw;
  }
}

VirtualPrinterLink::~VirtualPrinterLink() {
  link_.reset();
  if (log_ != nullptr) std::fclose(log_);
  if (model_fd_ >= 0) ::close(model_fd_);
  if (fd_ >= 0) ::close(fd_);
}

std::string VirtualPrinterLink::summary() const {
  const VirtualPrinterStats& v = printer_->stats();
  return fmt::format("virtual printer: executed {}, accepted lines {}, planner starved {:.2f} % of the print, "
                     "bytes lost to overruns {}, print time {:.1f} s simulated",
                     v.executed, v.accepted_lines, 100.0 * printer_->starvation(), v.overrun_bytes,
                     v.last_move_end > v.first_move ? v.last_move_end - v.first_move : 0.0);
}

bool VirtualPrinterLink::watched(double& end, double& queued) const {
  if (!printer_->watched().seen) return false;
  end = printer_->watched().motion_end;
  queued = printer_->watched().queued_length;
  return true;
}

}  // namespace gcode::serial
