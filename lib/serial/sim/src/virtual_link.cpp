#include "gcode/serial/sim/virtual_link.hpp"

#include <poll.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <limits>

namespace gcode::serial {

VirtualLink::VirtualLink(EventLoop& loop, VirtualPrinter& printer, int fd)
    : loop_(loop), printer_(printer), fd_(fd), wall0_(EventLoop::now()), scale_(printer.config().time_scale) {
  set_nonblocking(fd_);
  struct stat st {};
  socket_ = ::fstat(fd_, &st) == 0 && S_ISSOCK(st.st_mode);
  // The model wakes for every line it sends; the kernel's default 50 us
  // timer slack, multiplied by the time scale, would stretch the simulated
  // round trips.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  watch_ = loop_.add_fd(fd_, POLLIN, [this](short revents) { on_io(revents); });
  loop_.add_timer(
      [this] {
        if (closed_) return std::numeric_limits<double>::infinity();
        double t = printer_.next_event();
        return std::isinf(t) ? t : wall0_ + t / scale_;
      },
      [this](double) { pump(); });
  pump();
}

double VirtualLink::simulated_now() const { return (EventLoop::now() - wall0_) * scale_; }

void VirtualLink::on_io(short revents) {
  if (closed_) return;
  if (revents & POLLIN) {
    char buf[65536];
    double now = simulated_now();
    for (;;) {
      ssize_t n = ::read(fd_, buf, sizeof buf);
      if (n > 0) {
        printer_.advance(now);  // what happened before these bytes arrived
        printer_.receive(std::string_view(buf, static_cast<std::size_t>(n)), now);
        // A short read took all there was: the next poll says when there
        // is more (a read to find it empty would cost a system call each
        // time the host writes).
        if (static_cast<std::size_t>(n) < sizeof buf) break;
        continue;
      }
      if (n == 0) {
        // The host closed its end (a socketpair); a pty never gets here
        // because we keep its slave side open ourselves.
        loop_.set_events(watch_, 0);
        loop_.remove_fd(watch_);
        closed_ = true;
        return;
      }
      break;
    }
  }
  pump();
}

void VirtualLink::reset_printer() {
  double now = simulated_now();
  printer_.advance(now);
  printer_.reset(now);
  pump();
}

void VirtualLink::drop_link(double seconds, bool reset_after) {
  double now = simulated_now();
  printer_.advance(now);
  printer_.drop_link(now, seconds, reset_after);
  pump();
}

// The model's link went down or came back: the descriptor goes or a new one
// comes (a pty at the same path).
void VirtualLink::follow_link_state() {
  if (printer_.link_down() == down_) return;
  down_ = printer_.link_down();
  if (down_) {
    out_.clear();
    if (!on_drop_) return;
    loop_.remove_fd(watch_);
    watch_ = -1;
    on_drop_();
  } else if (on_restore_) {
    fd_ = on_restore_();
    set_nonblocking(fd_);
    watch_ = loop_.add_fd(fd_, POLLIN, [this](short revents) { on_io(revents); });
  }
}

void VirtualLink::pump() {
  if (closed_) return;
  double now = simulated_now();
  printer_.advance(now);
  follow_link_state();
  std::string_view ready = printer_.transmitted(now);
  out_.append(ready);
  printer_.take(ready.size());
  // The log goes out before the answers: whoever reads it after the host
  // got an answer finds the commands that ended before it.
  printer_.flush_log();
  if (watch_ < 0) {
    out_.clear();  // no link: the model's lines go nowhere
    return;
  }
  while (!out_.empty()) {
    // A socket whose host end is gone is EPIPE, never a SIGPIPE that would
    // end the whole process (gc-send runs the model in-process).
    ssize_t n = socket_ ? ::send(fd_, out_.data(), out_.size(), MSG_NOSIGNAL) : ::write(fd_, out_.data(), out_.size());
    if (n < 0 && errno == EPIPE) {
      loop_.set_events(watch_, 0);
      loop_.remove_fd(watch_);
      closed_ = true;
      return;
    }
    if (n <= 0) break;
    out_.erase(0, static_cast<std::size_t>(n));
  }
  loop_.set_events(watch_, static_cast<short>(POLLIN | (out_.empty() ? 0 : POLLOUT)));
  if (printer_.disconnected() && out_.empty()) {
    closed_ = true;
    loop_.remove_fd(watch_);
    if (on_close_) on_close_();
  }
}

}  // namespace gcode::serial
