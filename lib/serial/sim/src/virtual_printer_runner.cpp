#include "gcode/serial/sim/virtual_printer_runner.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <stdexcept>

#include "gcode/serial/link/event_loop.hpp"
#include "gcode/serial/link/port.hpp"
#include "gcode/serial/sim/virtual_link.hpp"

namespace gcode::serial {

namespace {

// The signals that end the run or fire a fault, taken from a descriptor so
// the loop sees them between events (blocked for the rest of the process).
class StopSignals {
 public:
  StopSignals() {
    sigset_t mask;
    sigemptyset(&mask);
    sigaddset(&mask, SIGINT);
    sigaddset(&mask, SIGTERM);
    sigaddset(&mask, SIGHUP);
    sigaddset(&mask, SIGUSR1);
    sigaddset(&mask, SIGUSR2);
    sigprocmask(SIG_BLOCK, &mask, nullptr);
    fd_ = signalfd(-1, &mask, SFD_CLOEXEC | SFD_NONBLOCK);
  }
  ~StopSignals() { ::close(fd_); }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  int fd() const { return fd_; }
  // The signal that arrived (0: none).
  int take() const {
    signalfd_siginfo info{};
    return ::read(fd_, &info, sizeof info) == static_cast<ssize_t>(sizeof info) ? static_cast<int>(info.ssi_signo) : 0;
  }

 private:
  int fd_ = -1;
};

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

std::string virtual_printer_summary(const VirtualPrinter& printer, bool link_dropped) {
  const VirtualPrinterStats& s = printer.stats();
  return fmt::format(
      "executed {}, accepted lines {}, checksum errors {}, line number errors {}, overrun bytes {}, planner starved "
      "{:.2f} %{}{}",
      s.executed, s.accepted_lines, s.checksum_errors, s.line_number_errors, s.overrun_bytes,
      100 * printer.starvation(),
      s.resets + s.link_drops > 0 ? fmt::format(", resets {}, link drops {}", s.resets, s.link_drops) : "",
      link_dropped ? ", link dropped" : "");
}

int run_virtual_printer(const VirtualPrinterRun& run, const VirtualPrinterConfig& config) {
  StopSignals signals;
  std::unique_ptr<std::FILE, FileCloser> log;
  if (!run.log.empty()) {
    log.reset(std::fopen(run.log.c_str(), "w"));
    if (!log) throw std::runtime_error(fmt::format("cannot write {}", run.log));
    // Buffered, and written out by the link each time the model has run
    // (VirtualLink::pump): whoever watches the log while the printer runs
    // (a test waiting for it to fall still) sees each command as it ends,
    // with one write for the commands of a turn instead of one each.
  }
  EventLoop loop;
  VirtualPrinter printer(config, log.get());
  auto pty = std::make_unique<PseudoTerminal>(run.link);
  if (!run.quiet)
    fmt::print(stderr, "{}: {} -> {}, {:g} baud, time scale {:g}\n", run.name, run.link, pty->slave_path(), config.baud,
               config.time_scale);
  VirtualLink link(loop, printer, pty->master());
  link.set_on_close([&loop] { loop.stop(); });
  // The host sees its port vanish (a hang-up, then no such file) and come
  // back at the same path, as a USB serial device does.
  link.set_on_drop([&pty] { pty.reset(); },
                   [&pty, &run] {
                     pty = std::make_unique<PseudoTerminal>(run.link);
                     return pty->master();
                   });
  loop.add_fd(signals.fd(), POLLIN, [&](short) {
    int sig = signals.take();
    if (sig == SIGUSR1) link.reset_printer();
    else if (sig == SIGUSR2) link.drop_link(run.drop_seconds, false);
    else loop.stop();
  });
  loop.run();
  log.reset();
  if (!run.quiet) fmt::print(stderr, "{}: {}\n", run.name, virtual_printer_summary(printer, link.closed()));
  return 0;
}

}  // namespace gcode::serial
