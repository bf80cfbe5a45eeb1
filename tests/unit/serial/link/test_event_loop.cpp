// One thread, one poll() (serial/event_loop.hpp): handlers run when their
// descriptor is ready and not once removed or muted, timers fire once their
// deadline has passed (not before), the loop ends when nothing is left to
// wait for or on stop().
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <limits>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "gcode/serial/link/event_loop.hpp"

using gcode::serial::EventLoop;

namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();

struct LoopPipe {
  int r = -1, w = -1;
  LoopPipe() {
    int fds[2];
    REQUIRE(::pipe(fds) == 0);
    r = fds[0];
    w = fds[1];
  }
  ~LoopPipe() {
    ::close(r);
    if (w >= 0) ::close(w);
  }
  void close_writer() {
    ::close(w);
    w = -1;
  }
};

}  // namespace

TEST_CASE("event loop: nothing to wait for ends at once", "[serial][event_loop]") {
  EventLoop loop;
  loop.run();
  loop.add_timer([] { return kNever; }, [](double) { FAIL("an idle timer fired"); });
  loop.run();
  CHECK_FALSE(loop.stopped());
}

TEST_CASE("event loop: a readable descriptor calls its handler with the events", "[serial][event_loop]") {
  EventLoop loop;
  LoopPipe p;
  REQUIRE(::write(p.w, "ok\nok\n", 6) == 6);
  std::string got;
  int id = 0;
  id = loop.add_fd(p.r, POLLIN, [&](short revents) {
    CHECK((revents & POLLIN) != 0);
    char b[2];
    ssize_t n = ::read(p.r, b, sizeof b);  // two bytes at a time: called again
    if (n > 0) got.append(b, static_cast<std::size_t>(n));
    if (got.size() == 6) loop.remove_fd(id);
  });
  loop.run();  // ends once the only watch is removed
  CHECK(got == "ok\nok\n");
}

TEST_CASE("event loop: a muted watch is not polled, a hang-up is reported", "[serial][event_loop]") {
  EventLoop loop;
  LoopPipe muted, live;
  REQUIRE(::write(muted.w, "x", 1) == 1);
  int calls = 0;
  int muted_id = loop.add_fd(muted.r, POLLIN, [&](short) { FAIL("a muted watch ran"); });
  loop.set_events(muted_id, 0);
  live.close_writer();
  int live_id = 0;
  live_id = loop.add_fd(live.r, POLLIN, [&](short revents) {
    ++calls;
    CHECK((revents & POLLHUP) != 0);
    loop.remove_fd(live_id);
  });
  loop.run();
  CHECK(calls == 1);
}

TEST_CASE("event loop: timers fire once their deadline has passed", "[serial][event_loop]") {
  EventLoop loop;
  const double start = EventLoop::now();
  double deadline = start + 0.02;
  std::vector<double> fired;
  loop.add_timer([&] { return deadline; },
                 [&](double now) {
                   fired.push_back(now);
                   CHECK(now >= deadline);
                   deadline = fired.size() < 3 ? now + 0.01 : kNever;
                 });
  loop.run();  // ends when the timer has nothing more to do
  REQUIRE(fired.size() == 3);
  CHECK(fired[0] - start >= 0.02);
  CHECK(fired[2] - start >= 0.04);
  CHECK(fired[2] - start < 1.0);  // slept, did not hang
  CHECK(EventLoop::now() >= fired[2]);
}

TEST_CASE("event loop: a timer due now and a ready descriptor both run, stop() ends the loop", "[serial][event_loop]") {
  EventLoop loop;
  LoopPipe p;
  REQUIRE(::write(p.w, "x", 1) == 1);
  int io = 0, timer = 0;
  loop.add_fd(p.r, POLLIN, [&](short) {
    ++io;
    char b;
    CHECK(::read(p.r, &b, 1) == 1);
  });
  loop.add_timer([] { return 0.0; },  // always due
                 [&](double) {
                   if (++timer == 3) loop.stop();
                 });
  loop.run();
  CHECK(loop.stopped());
  CHECK(timer == 3);
  CHECK(io == 1);
}

TEST_CASE("event loop: set_nonblocking", "[serial][event_loop]") {
  LoopPipe p;
  gcode::serial::set_nonblocking(p.r);
  CHECK((::fcntl(p.r, F_GETFL) & O_NONBLOCK) != 0);
  char b;
  CHECK(::read(p.r, &b, 1) == -1);
  CHECK(errno == EAGAIN);
  CHECK_THROWS_AS(gcode::serial::set_nonblocking(-1), std::system_error);
}

TEST_CASE("event loop: a handler may add watches while it runs", "[serial][event_loop]") {
  // The handler captures one pointer, as the session's [this] handlers do:
  // std::function keeps such a small closure inside itself, so moving the
  // watch list under the running call would leave it reading freed memory.
  struct Ctx {
    EventLoop loop;
    LoopPipe first;
    std::vector<std::unique_ptr<LoopPipe>> more;
    int served = 0;
    int first_id = 0;
  } ctx;
  REQUIRE(::write(ctx.first.w, "x", 1) == 1);
  Ctx* c = &ctx;
  ctx.first_id = ctx.loop.add_fd(ctx.first.r, POLLIN, [c](short) {
    char b;
    CHECK(::read(c->first.r, &b, 1) == 1);
    for (int i = 0; i < 64; ++i) {
      c->more.push_back(std::make_unique<LoopPipe>());
      LoopPipe* p = c->more.back().get();
      REQUIRE(::write(p->w, "y", 1) == 1);
      c->loop.add_fd(p->r, POLLIN, [c, p](short) {
        char y;
        CHECK(::read(p->r, &y, 1) == 1);
        ++c->served;
      });
    }
    c->loop.remove_fd(c->first_id);  // `c` read after the additions
  });
  ctx.loop.add_timer([c] { return c->served == 64 ? 0.0 : kNever; }, [c](double) { c->loop.stop(); });
  ctx.loop.run();
  CHECK(ctx.served == 64);
}

TEST_CASE("event loop: a timer may add timers when it fires", "[serial][event_loop]") {
  struct Ctx {
    EventLoop loop;
    int added = 0;
    int fired = 0;
    double due = 0;  // the first timer's deadline: now
  } ctx;
  Ctx* c = &ctx;
  ctx.loop.add_timer([c] { return c->due; },
                     [c](double) {
                       c->due = kNever;
                       for (int i = 0; i < 64; ++i) {
                         ++c->added;
                         c->loop.add_timer([c] { return c->fired < c->added ? 0.0 : kNever; }, [c](double) { ++c->fired; });
                       }
                       c->due = kNever;  // `c` read after the additions
                     });
  ctx.loop.run();  // ends once every timer is idle
  CHECK(ctx.added == 64);
  CHECK(ctx.fired == 64);
}
