#pragma once
// One thread, one poll(): file descriptors and timers. Nothing spins: the
// loop sleeps until a descriptor is ready or the earliest timer is due, so
// the CPU stays idle while a slow printer works.
#include <deque>
#include <functional>

namespace gcode::serial {

class EventLoop {
 public:
  using IoHandler = std::function<void(short revents)>;
  // A timer asks for its deadline (monotonic seconds, or infinity) before
  // every sleep, and is fired once the deadline has passed.
  using Deadline = std::function<double()>;
  using Fire = std::function<void(double now)>;

  int add_fd(int fd, short events, IoHandler handler);
  void set_events(int id, short events);
  void remove_fd(int id);
  void add_timer(Deadline deadline, Fire fire);

  // Runs until stop() or until nothing is left to wait for.
  void run();
  void stop() { stopped_ = true; }
  bool stopped() const { return stopped_; }

  // Monotonic clock in seconds.
  static double now();
  // From now on (for the whole process) now() is a simulated clock that
  // moves only when the loop would sleep (it jumps to the earliest timer's
  // deadline instead) and by `per_wake` seconds each time the loop wakes
  // to handle something (the host's latency, as on a quiet machine). For a
  // run whose other end is in the process (gc-send --port
  // virtual:simulated-clock): the host's speed and load do not count, so
  // its figures are the same on any machine. A loop with nothing ready and
  // no timer still sleeps for real.
  static void use_simulated_clock(double per_wake);

 private:
  struct Watch {
    int fd;
    short events;
    IoHandler handler;
    bool removed = false;
  };
  struct Timer {
    Deadline deadline;
    Fire fire;
  };
  // A deque: a handler may add watches while it runs, and its own (a closure
  // std::function holds inline) must not move under it.
  std::deque<Watch> watches_;
  std::deque<Timer> timers_;  // a deque for the same reason: fire() may add timers
  bool stopped_ = false;
  static bool simulated_;
  static double simulated_now_;
  static double simulated_wake_;
  static double wake_latency();
};

// Makes a descriptor non-blocking (throws std::system_error on failure).
void set_nonblocking(int fd);

}  // namespace gcode::serial
