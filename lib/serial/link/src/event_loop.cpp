#include "gcode/serial/link/event_loop.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>

#include <cerrno>
#include <cmath>
#include <ctime>
#include <limits>
#include <random>
#include <system_error>
#include <vector>

namespace gcode::serial {

bool EventLoop::simulated_ = false;
double EventLoop::simulated_now_ = 0;
double EventLoop::simulated_wake_ = 0;

// A host's latency is no constant: exponential about its mean, from a
// fixed seed (the same run gives the same figures).
double EventLoop::wake_latency() {
  static std::mt19937 rng(1);
  if (simulated_wake_ <= 0) return 0;
  return std::exponential_distribution<double>(1 / simulated_wake_)(rng);
}

void EventLoop::use_simulated_clock(double per_wake) {
  simulated_now_ = now();
  simulated_wake_ = per_wake;
  simulated_ = true;
}

double EventLoop::now() {
  if (simulated_) return simulated_now_;
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
    // The simulated clock does not sleep: it looks, and when nothing is
    // ready it moves on to the earliest deadline.
    const bool jump = simulated_ && earliest != std::numeric_limits<double>::infinity();
    if (jump) {
      timeout_ptr = &timeout;
    } else if (earliest != std::numeric_limits<double>::infinity()) {
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
    // A nanosecond past it: a deadline converted from another clock (the
    // model's simulated seconds, virtual_link.cpp) may round to just
    // before the time it stands for, and the loop would stand still.
    if (jump && n == 0) simulated_now_ = std::max(simulated_now_, earliest) + 1e-9;
    if (simulated_) simulated_now_ += wake_latency();
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
