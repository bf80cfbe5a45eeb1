// What the printer says before a resume (gcode/serial/job/printer_probe.hpp):
// a port that closes while it is asked is a PortLost (gc-send waits for it
// to come back), a printer that never names its last line a problem.
#include <catch2/catch.hpp>

#include <sys/socket.h>
#include <unistd.h>

#include <string>

#include "gcode/serial/job/printer_probe.hpp"

using namespace gcode::serial;

TEST_CASE("printer probe: a port that closes while asked is lost", "[serial][printer_probe]") {
  int fds[2];
  REQUIRE(::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) == 0);
  ::close(fds[1]);  // the printer's end gone
  CHECK_THROWS_AS(probe_printer(fds[0], 0.2, {}), PortLost);
  ::close(fds[0]);
}

TEST_CASE("printer probe: a silent printer names no last line", "[serial][printer_probe]") {
  int fds[2];
  REQUIRE(::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) == 0);
  std::string sent;
  ProbeResult r = probe_printer(fds[0], 0.1, [&sent](std::string_view line) { sent += std::string(line) + "\n"; });
  CHECK_FALSE(r.answered);
  CHECK(r.problem.find("did not say which line it took last") != std::string::npos);
  CHECK(sent.find("M105") != std::string::npos);  // the mis-numbered question went out
  ::close(fds[0]);
  ::close(fds[1]);
}
