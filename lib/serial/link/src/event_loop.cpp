#include "gcode/serial/link/event_loop.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>

#include <cerrno>
#include <cmath>
#include <ctime>
#include <limits>
#include <system_error>
#include <vector>

namespace gcode::serial {

double EventLoop::now() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

int EventLoop::add_fd(int fd, short events, IoHandler handler) {
  watches_.push_back({fd, events, std::move(handler)});
  return static_cast<int>(watches_.size() - 1);
}

void EventLoop::set_events(int id, short events) { watches_[static_cast<std::size_t>(id)].events = events; }

void EventLoop::remove_fd(int id) {
  Watch& w = watches_[static_cast<std::size_t>(id)];
  w.removed = true;
  w.events = 0;
}

void EventLoop::add_timer(Deadline deadline, Fire fire) { timers_.push_back({std::move(deadline), std::move(fire)}); }

void set_nonblocking(int fd) {
  int flags = fcntl(fd, F_GETFL);
  if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0)
    throw std::system_error(errno, std::generic_category(), "fcntl");
}

void EventLoop::run() {
  // Timers here pace a link byte by byte (a simulated printer at a high time
  // scale answers within tens of microseconds): Linux's default 50 us slack
  // on every sleep would add up to most of a round trip.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  std::vector<pollfd> fds;
  std::vector<std::size_t> ids;
  while (!stopped_) {
    double earliest = std::numeric_limits<double>::infinity();
    for (const Timer& t : timers_) earliest = std::min(earliest, t.deadline());
    fds.clear();
    ids.clear();
    for (std::size_t i = 0; i < watches_.size(); ++i) {
      if (watches_[i].removed || watches_[i].events == 0) continue;
      fds.push_back({watches_[i].fd, watches_[i].events, 0});
      ids.push_back(i);
    }
    if (fds.empty() && earliest == std::numeric_limits<double>::infinity()) return;
    timespec timeout{};
    timespec* timeout_ptr = nullptr;
    if (earliest != std::numeric_limits<double>::infinity()) {
      double wait = std::max(0.0, earliest - now());
      wait = std::min(wait, 3600.0);
      timeout.tv_sec = static_cast<time_t>(wait);
      timeout.tv_nsec = static_cast<long>((wait - std::floor(wait)) * 1e9);
      timeout_ptr = &timeout;
    }
    int n = ppoll(fds.data(), fds.size(), timeout_ptr, nullptr);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::system_error(errno, std::generic_category(), "poll");
    }
    for (std::size_t k = 0; k < fds.size() && n > 0 && !stopped_; ++k) {
      if (fds[k].revents == 0) continue;
      Watch& w = watches_[ids[k]];
      if (!w.removed) w.handler(fds[k].revents);
    }
    double t = now();
    for (std::size_t i = 0; i < timers_.size() && !stopped_; ++i)
      if (timers_[i].deadline() <= t) timers_[i].fire(t);
  }
}

}  // namespace gcode::serial
