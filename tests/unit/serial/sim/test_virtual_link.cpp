// A virtual printer at the end of a descriptor (serial/virtual_link.hpp):
// its greeting and answers cross a socketpair as the model sends them, its
// clock runs at the time scale, and the link closes when the host hangs up
// or the model drops the line.
#include <catch2/catch.hpp>

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>

#include "gcode/serial/protocol/protocol.hpp"
#include "gcode/serial/sim/virtual_link.hpp"

using gcode::serial::EventLoop;
using gcode::serial::VirtualLink;
using gcode::serial::VirtualPrinter;
using gcode::serial::VirtualPrinterConfig;

namespace {

struct SocketPair {
  int host = -1, model = -1;
  SocketPair() {
    int fds[2];
    REQUIRE(::socketpair(AF_UNIX, SOCK_STREAM, 0, fds) == 0);
    host = fds[0];
    model = fds[1];
  }
  ~SocketPair() {
    if (host >= 0) ::close(host);
    ::close(model);
  }
};

// The host's side of a conversation: sends `script[i]` after the i-th answer
// line, collects every line, stops after `lines` lines or a time limit.
std::vector<std::string> converse(EventLoop& loop, int host, const std::vector<std::string>& script, std::size_t lines) {
  std::vector<std::string> got;
  std::string partial;
  int id = 0;
  id = loop.add_fd(host, POLLIN, [&](short) {
    char b[512];
    ssize_t n = ::read(host, b, sizeof b);
    if (n <= 0) return loop.remove_fd(id);
    partial.append(b, static_cast<std::size_t>(n));
    for (std::size_t nl; (nl = partial.find('\n')) != std::string::npos; partial.erase(0, nl + 1)) {
      got.push_back(partial.substr(0, nl));
      if (got.size() <= script.size()) {
        const std::string& s = script[got.size() - 1];
        REQUIRE(::write(host, s.data(), s.size()) == static_cast<ssize_t>(s.size()));
      }
      if (got.size() >= lines) loop.stop();
    }
  });
  const double give_up = EventLoop::now() + 5;
  loop.add_timer([&] { return give_up; }, [&](double) { loop.stop(); });
  loop.run();
  return got;
}

}  // namespace

TEST_CASE("virtual link: greeting and answers cross the socketpair", "[serial][virtual_link]") {
  SocketPair s;
  VirtualPrinterConfig c;
  c.time_scale = 10;
  VirtualPrinter printer(c);
  EventLoop loop;
  VirtualLink link(loop, printer, s.model);
  std::string numbered;
  gcode::serial::append_numbered_line(numbered, 1, "G90");
  auto got = converse(loop, s.host, {"M110 N0\n", numbered}, 3);
  CHECK(got == std::vector<std::string>{"start", "ok", "ok"});
  CHECK(printer.stats().accepted_lines == 1);
  CHECK_FALSE(link.closed());
}

TEST_CASE("virtual link: simulated time runs at the time scale", "[serial][virtual_link]") {
  SocketPair s;
  VirtualPrinterConfig c;
  c.time_scale = 50;
  VirtualPrinter printer(c);
  EventLoop loop;
  VirtualLink link(loop, printer, s.model);
  double wall = EventLoop::now();
  ::usleep(40000);
  double simulated = link.simulated_now();
  double elapsed = EventLoop::now() - wall;
  CHECK(simulated >= 50 * 0.04);
  CHECK(simulated <= 50 * (elapsed + 0.01));
}

TEST_CASE("virtual link: the host hanging up closes the link", "[serial][virtual_link]") {
  SocketPair s;
  VirtualPrinter printer(VirtualPrinterConfig{});
  EventLoop loop;
  VirtualLink link(loop, printer, s.model);
  bool closed_called = false;
  link.set_on_close([&] { closed_called = true; });
  ::close(s.host);
  s.host = -1;
  loop.run();  // ends by itself: nothing left to wait for
  CHECK(link.closed());
  CHECK_FALSE(closed_called);  // the callback is for the model dropping the line
}

TEST_CASE("virtual link: a disconnect fault drops the line and says so", "[serial][virtual_link]") {
  SocketPair s;
  VirtualPrinterConfig c;
  c.time_scale = 10;
  c.disconnect_after = 1;
  VirtualPrinter printer(c);
  EventLoop loop;
  VirtualLink link(loop, printer, s.model);
  bool closed_called = false;
  link.set_on_close([&] {
    closed_called = true;
    loop.stop();
  });
  converse(loop, s.host, {"G90\n", "G90\n", "G90\n"}, 10);
  CHECK(printer.disconnected());
  CHECK(link.closed());
  CHECK(closed_called);
}
