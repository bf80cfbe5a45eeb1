// The simulated printer at the far end of gc-send's line
// (gcode/serial/sim/virtual_printer_link.hpp): the port names that choose
// it, its link's figures from the configuration, its greeting through the
// socketpair, its motion and its summary.
#include <catch2/catch.hpp>

#include <poll.h>
#include <unistd.h>

#include <string>

#include "gcode/serial/link/event_loop.hpp"
#include "gcode/serial/sim/virtual_printer_link.hpp"

using namespace gcode::serial;

TEST_CASE("virtual printer link: the port names that choose it", "[serial][virtual_printer_link]") {
  CHECK(is_virtual_port("virtual"));
  CHECK(is_virtual_port("virtual:time-scale=20"));
  CHECK_FALSE(is_virtual_port("virtualx"));
  CHECK_FALSE(is_virtual_port("/dev/ttyACM0"));
  CHECK_FALSE(is_virtual_port(""));
}

TEST_CASE("virtual printer link: greets through its socketpair, tells its motion", "[serial][virtual_printer_link]") {
  VirtualPrinterConfig config;
  config.time_scale = 10;
  config.baud = 115200;
  EventLoop loop;
  VirtualPrinterLink link(loop, config);
  CHECK(link.fd() >= 0);
  CHECK(link.baud() == 115200);
  CHECK(link.time_scale() == 10);
  CHECK_FALSE(link.pty());
  CHECK_FALSE(link.reconnects());  // it ends with the gc-send that runs it
  REQUIRE(link.motion() != nullptr);
  std::string got;
  int id = loop.add_fd(link.fd(), POLLIN, [&](short) {
    char b[256];
    ssize_t n = ::read(link.fd(), b, sizeof b);
    if (n > 0) got.append(b, static_cast<std::size_t>(n));
    if (n <= 0 || got.find('\n') != std::string::npos) loop.stop();
  });
  const double give_up = EventLoop::now() + 5;
  loop.add_timer([&] { return give_up; }, [&](double) { loop.stop(); });
  loop.run();
  loop.remove_fd(id);
  CHECK(got.rfind("start", 0) == 0);
  CHECK(link.motion()->now() > 0);
  CHECK(link.motion()->travelled(link.motion()->now()) == 0);  // nothing moved
  double end = 0, queued = 0;
  CHECK_FALSE(link.motion()->watched(end, queued));  // nothing watched
  CHECK(link.summary().rfind("virtual printer: executed 0, accepted lines 0", 0) == 0);
}
