// gc-send --reconnect (gcode/serial/job/port_reconnect.hpp): a lost port is
// waited for at its path, tried every tenth of a second on the caller's
// clock, until it is back (the sender told) or the time given has passed,
// or somebody gives up; without a path or time the print ends at once.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <limits>
#include <string>

#include "gcode/core/diagnostics.hpp"
#include "gcode/serial/job/port_reconnect.hpp"
#include "gcode/serial/link/port.hpp"
#include "gcode/serial/sender/sender.hpp"
#include "test_support.hpp"

using namespace gcode;
using namespace gcode::serial;

namespace test_port_reconnect {

struct Rig {
  Rig() : sender(config(), [](LogLevel, std::uint64_t, std::string_view) {}) { sender.start(0); }
  static SenderConfig config() {
    SenderConfig c;
    c.handshake = false;
    return c;
  }
  Diagnostics diag{"gc-send"};
  Sender sender;
};

}  // namespace test_port_reconnect

TEST_CASE("port reconnect: without --reconnect a lost port ends the print", "[serial][port_reconnect]") {
  test_port_reconnect::Rig rig;
  PortReconnect none(rig.sender, rig.diag, "", PortOptions{}, 5);
  CHECK_FALSE(none.lost("end of file", 1));
  CHECK_FALSE(none.waiting());
  CHECK(rig.sender.finished());
  test_port_reconnect::Rig rig2;
  PortReconnect no_time(rig2.sender, rig2.diag, "/dev/ttyACM0", PortOptions{}, 0);
  CHECK_FALSE(no_time.lost("end of file", 1));
  CHECK(rig2.sender.finished());
}

TEST_CASE("port reconnect: tried every tenth of a second until the time given has passed",
          "[serial][port_reconnect]") {
  test_port_reconnect::Rig rig;
  const std::string path = gctest::temp_dir() + "/never-there";
  PortReconnect reconnect(rig.sender, rig.diag, path, PortOptions{}, 2);
  CHECK(reconnect.next_try() == std::numeric_limits<double>::infinity());
  REQUIRE(reconnect.lost("Input/output error", 10));
  CHECK(reconnect.waiting());
  CHECK_FALSE(rig.sender.finished());
  CHECK(reconnect.next_try() == Approx(10.1));
  CHECK(reconnect.attempt(11) == -1);
  CHECK(reconnect.waiting());
  CHECK(reconnect.next_try() == Approx(11.1));
  CHECK(reconnect.attempt(12) == -1);  // two seconds gone
  CHECK_FALSE(reconnect.waiting());
  CHECK(rig.sender.finished());
  CHECK(rig.sender.failure().find("did not come back within 2 s") != std::string::npos);
}

TEST_CASE("port reconnect: a port that is back is opened and the sender told", "[serial][port_reconnect]") {
  test_port_reconnect::Rig rig;
  const std::string path = gctest::temp_dir() + "/printer";
  PseudoTerminal pty(path);
  PortReconnect reconnect(rig.sender, rig.diag, path, PortOptions{}, 5);
  REQUIRE(reconnect.lost("Input/output error", 0));
  const int fd = reconnect.attempt(0.1);
  REQUIRE(fd >= 0);
  CHECK_FALSE(reconnect.waiting());
  CHECK_FALSE(rig.sender.finished());
  // Asking the printer where it is: something to send.
  CHECK_FALSE(rig.sender.output().empty());
  ::close(fd);
}

TEST_CASE("port reconnect: giving up ends the print with the reason", "[serial][port_reconnect]") {
  test_port_reconnect::Rig rig;
  PortReconnect reconnect(rig.sender, rig.diag, gctest::temp_dir() + "/away", PortOptions{}, 60);
  REQUIRE(reconnect.lost("end of file", 0));
  reconnect.give_up("interrupted while waiting for the port to come back");
  CHECK_FALSE(reconnect.waiting());
  CHECK(rig.sender.finished());
  CHECK(rig.sender.failure().find("interrupted") != std::string::npos);
}
