#include "gcode/serial/send_session.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include <fmt/format.h>

#include "gcode/core/line.hpp"
#include "gcode/serial/protocol.hpp"

namespace gcode::serial {

SendSession::SendSession(EventLoop& loop, Sender& sender, int input_fd, int port_fd, Diagnostics& diagnostics)
    : loop_(loop),
      sender_(sender),
      input_fd_(input_fd),
      port_fd_(port_fd),
      diag_(diagnostics),
      // Small reads: the sender takes lines as the printer needs them, and
      // stages before it should not run far ahead of the print.
      pipeline_(markers_, PipelineOptions{.layers = true, .block_size = 16384}) {
  pipeline_.add(*this);
  set_nonblocking(port_fd_);
  sigset_t mask;
  sigemptyset(&mask);
  sigaddset(&mask, SIGINT);
  sigaddset(&mask, SIGTERM);
  sigprocmask(SIG_BLOCK, &mask, &saved_mask_);
  signal_fd_ = signalfd(-1, &mask, SFD_CLOEXEC | SFD_NONBLOCK);
  if (signal_fd_ >= 0) loop_.add_fd(signal_fd_, POLLIN, [this](short) { on_signal(); });
  input_watch_ = loop_.add_fd(input_fd_, POLLIN, [this](short) { read_input(); });
  port_watch_ = loop_.add_fd(port_fd_, POLLIN, [this](short revents) {
    if (revents & (POLLIN | POLLHUP | POLLERR)) read_port();
    update();
  });
  loop_.add_timer([this] { return sender_.deadline(); },
                  [this](double now) {
                    sender_.on_timer(now);
                    update();
                  });
}

SendSession::~SendSession() {
  if (signal_fd_ >= 0) ::close(signal_fd_);
  // Back to the mask the caller had (a signal it blocked itself stays blocked).
  sigprocmask(SIG_SETMASK, &saved_mask_, nullptr);
}

void SendSession::run() {
  sender_.start(EventLoop::now());
  update();
  if (!loop_.stopped()) loop_.run();
}

void SendSession::line(const TrackedLine& t, Emitter&) {
  ++input_lines_;
  const Line& line = t.line;
  // Blank or comment only; a line that is neither (binary junk) goes to the
  // sender, which refuses what the firmware cannot read.
  if (line.kind == CommandKind::None && !line.malformed) return;
  if (line.kind == CommandKind::Host) {
    // "@pause" and friends are for the host, never for the firmware.
    ++host_commands_;
    diag_.info(fmt::format("line {}: host command '{}' not sent to the printer", t.raw.number, line.code()));
    return;
  }
  std::string_view command = command_for_sending(line, scratch_);
  if (command.empty()) return;
  if (line.is_m(110)) {
    diag_.warn(t.raw.number, "M110 not sent: gc-send numbers the lines itself");
    return;
  }
  sender_.submit(command, t.raw.number, t.layer);
}

void SendSession::read_input() {
  bool more = true;
  try {
    more = pipeline_.read_some(input_fd_);
  } catch (const std::system_error& e) {
    if (e.code().value() == EAGAIN) return;
    throw std::runtime_error(fmt::format("cannot read the input: {}", std::strerror(e.code().value())));
  }
  if (!more) {
    input_done_ = true;
    sender_.end_of_input();
    loop_.set_events(input_watch_, 0);
    loop_.remove_fd(input_watch_);
  }
  update();
}

void SendSession::read_port() {
  char buf[4096];
  for (;;) {
    ssize_t n = ::read(port_fd_, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN) break;
    if (n <= 0) {
      sender_.disconnected(n == 0 ? "end of file" : std::strerror(errno));
      loop_.set_events(port_watch_, 0);
      loop_.remove_fd(port_watch_);
      port_watch_ = -1;
      return;
    }
    double now = EventLoop::now();
    port_in_.append(buf, static_cast<std::size_t>(n));
    std::size_t pos = 0;
    for (std::size_t nl; (nl = port_in_.find('\n', pos)) != std::string::npos; pos = nl + 1) {
      std::string_view line = std::string_view(port_in_).substr(pos, nl - pos);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      sender_.on_line(line, now);
    }
    port_in_.erase(0, pos);
    if (port_in_.size() > 4096) port_in_.clear();  // no newline in 4 KB: line noise
  }
}

void SendSession::flush_port() {
  while (!sender_.output().empty()) {
    std::string_view out = sender_.output();
    ssize_t n = ::write(port_fd_, out.data(), out.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN) break;
    if (n < 0) {
      sender_.disconnected(std::strerror(errno));
      return;
    }
    sender_.written(static_cast<std::size_t>(n), EventLoop::now());
  }
}

void SendSession::on_signal() {
  signalfd_siginfo info{};
  while (::read(signal_fd_, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
    ++interrupts_;
    if (interrupts_ == 1) {
      diag_.error(fmt::format("interrupted: sending stops, waiting for {} lines in flight; "
                              "press Ctrl-C again for an emergency stop (M112)",
                              sender_.in_flight()));
      sender_.cancel();
      if (!input_done_) {
        loop_.set_events(input_watch_, 0);
        loop_.remove_fd(input_watch_);
        input_done_ = true;
      }
    } else if (!sender_.emergency()) {
      diag_.error("emergency stop: M112 sent");
      sender_.emergency_stop();
    }
  }
  update();
}

void SendSession::update() {
  sender_.pump(EventLoop::now());
  flush_port();
  if (sender_.finished() && sender_.output().empty()) {
    loop_.stop();
    return;
  }
  if (port_watch_ >= 0)
    loop_.set_events(port_watch_, static_cast<short>(POLLIN | (sender_.output().empty() ? 0 : POLLOUT)));
  if (!input_done_) loop_.set_events(input_watch_, sender_.wants_input() ? POLLIN : 0);
}

}  // namespace gcode::serial
