#include "gcode/serial/job/printer_probe.hpp"

#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/serial/link/event_loop.hpp"
#include "gcode/serial/protocol/printer_report.hpp"
#include "gcode/serial/protocol/protocol.hpp"

namespace gcode::serial {

namespace {

// A number no print reaches: the printer refuses the line and names the
// last one it took.
constexpr long long kProbeNumber = 999999999;
constexpr double kQuiet = 0.3;  // seconds of silence that end a drain

class Exchange {
 public:
  Exchange(int fd, const std::function<void(std::string_view)>& trace) : fd_(fd), trace_(trace) {}

  void send(std::string_view text) {
    if (trace_) trace_(fmt::format("-> {}", text.substr(0, text.find('\n'))));
    while (!text.empty()) {
      ssize_t n = ::write(fd_, text.data(), text.size());
      if (n < 0 && (errno == EINTR || errno == EAGAIN)) {
        wait(POLLOUT, 0.1);
        continue;
      }
      if (n < 0) throw PortLost(fmt::format("cannot write to the printer: {}", std::strerror(errno)));
      text.remove_prefix(static_cast<std::size_t>(n));
    }
  }

  // Lines until `done` says so (true), `quiet` seconds pass without a byte
  // (with quiet > 0) or `timeout` passes; false when it was not `done`.
  bool read(double timeout, double quiet, const std::function<bool(std::string_view)>& done) {
    double end = EventLoop::now() + timeout;
    double last = EventLoop::now();
    for (;;) {
      std::size_t nl;
      while ((nl = pending_.find('\n')) != std::string::npos) {
        std::string line = pending_.substr(0, nl);
        pending_.erase(0, nl + 1);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (trace_) trace_(fmt::format("<- {}", line));
        if (done(line)) return true;
      }
      double now = EventLoop::now();
      if (now >= end || (quiet > 0 && now - last >= quiet)) return false;
      double wait_for = std::min(end - now, quiet > 0 ? quiet - (now - last) : end - now);
      if (!wait(POLLIN, wait_for)) continue;
      char buf[4096];
      ssize_t n = ::read(fd_, buf, sizeof buf);
      if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      if (n <= 0)
        throw PortLost(fmt::format("the printer's port closed while gc-send asked where it is ({})",
                                   n == 0 ? "end of file" : std::strerror(errno)));
      pending_.append(buf, static_cast<std::size_t>(n));
      last = EventLoop::now();
    }
  }

 private:
  bool wait(short events, double seconds) {
    pollfd p{fd_, events, 0};
    int ms = static_cast<int>(std::max(0.0, seconds) * 1000) + 1;
    return ::poll(&p, 1, ms) > 0;
  }
  int fd_;
  const std::function<void(std::string_view)>& trace_;
  std::string pending_;
};

}  // namespace

ProbeResult probe_printer(int fd, double timeout, const std::function<void(std::string_view)>& trace) {
  ProbeResult r;
  Exchange x(fd, trace);
  auto note = [&r](std::string_view line) {
    if (is_restart_line(line)) r.greeted = true;
    if (auto last = last_line_of(line)) {
      r.last_line = *last;
      r.answered = true;
    }
  };
  // What the printer said while nobody listened, then a newline that ends
  // any line cut off when the old gc-send died (refused: it has no checksum).
  x.read(2, kQuiet, [&](std::string_view line) { note(line); return false; });
  x.send("\n");
  x.read(timeout, kQuiet, [&](std::string_view line) { note(line); return false; });
  std::string probe;
  append_numbered_line(probe, kProbeNumber, "M105");
  r.answered = false;
  for (int attempt = 0; attempt < 3 && !r.answered; ++attempt) {
    x.send(probe);
    bool resend = false;
    // Error ... Last Line: n, Resend: n+1, ok: then quiet.
    x.read(timeout, 0, [&](std::string_view line) {
      note(line);
      Response resp = parse_response(line);
      if (resp.kind == ResponseKind::Resend) resend = true;
      return resend && resp.kind == ResponseKind::Ok;
    });
  }
  if (!r.answered) {
    r.problem = "the printer did not say which line it took last (no answer to a mis-numbered line)";
    return r;
  }
  // Every move the printer took has run once M400 is answered: the line it
  // took last then surely ran (a reset later goes back no further), and
  // M114 says where the head stands, not where its queue ends. A busy line
  // while it waits keeps the wait going.
  x.send("M400\n");
  bool drained = false;
  while (!drained && x.read(timeout, 0, [&](std::string_view line) {
    note(line);
    Response resp = parse_response(line);
    drained = resp.kind == ResponseKind::Ok;
    return drained || resp.kind == ResponseKind::Busy;
  })) {
  }
  if (!drained) {
    r.problem = "the printer did not finish the moves it had taken (no answer to M400)";
    return r;
  }
  x.send("M114\n");
  std::optional<PositionReport> position;
  x.read(timeout, 0, [&](std::string_view line) {
    note(line);
    if (!position) position = parse_position_report(line);
    return position && parse_response(line).kind == ResponseKind::Ok;
  });
  r.findings.position = position;
  r.findings.expected_line = r.last_line + 1;
  r.findings.condition = r.greeted || r.last_line == 0 ? PrinterCondition::Reset : PrinterCondition::KeptRunning;
  if (!position) r.problem = "the printer did not report its position (M114)";
  return r;
}

}  // namespace gcode::serial
