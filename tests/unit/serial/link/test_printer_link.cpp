// The printer at the far end of gc-send's line (gcode/serial/link/printer_link.hpp):
// a PortLink on a device or pseudo-terminal carries bytes both ways, may come
// back after a drop, tells no motion and no summary, and closes its port.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <string>

#include "gcode/serial/link/port.hpp"
#include "gcode/serial/link/printer_link.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

namespace test_printer_link {

// What arrives on `fd` within a second, up to a newline.
std::string read_line(int fd) {
  std::string got;
  while (got.find('\n') == std::string::npos) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 1000) <= 0) break;
    char b[64];
    ssize_t n = ::read(fd, b, sizeof b);
    if (n <= 0) break;
    got.append(b, static_cast<std::size_t>(n));
  }
  return got;
}

bool is_open(int fd) { return ::fcntl(fd, F_GETFD) != -1; }

}  // namespace test_printer_link

TEST_CASE("printer link: a port link carries bytes and closes its port", "[serial][printer_link]") {
  const std::string path = gctest::temp_dir() + "/printer_link";
  PseudoTerminal printer(path);
  const PortOptions options{115200, false};
  int fd = -1;
  {
    PortLink link(path, options, open_serial_port(path, options));
    fd = link.fd();
    CHECK(fd >= 0);
    CHECK(link.pty());
    CHECK(link.baud() == 115200);
    CHECK(link.time_scale() == 1);
    CHECK(link.reconnects());  // a device's node may come back
    CHECK(link.motion() == nullptr);
    CHECK(link.summary().empty());
    REQUIRE(::write(link.fd(), "M105\n", 5) == 5);
    CHECK(test_printer_link::read_line(printer.master()) == "M105\n");
    REQUIRE(::write(printer.master(), "ok T:20\n", 8) == 8);
    CHECK(test_printer_link::read_line(link.fd()) == "ok T:20\n");
    link.reopen(1);  // the port opened again (no DTR pulse)
    CHECK(link.fd() >= 0);
    fd = link.fd();
  }
  CHECK_FALSE(test_printer_link::is_open(fd));
}

TEST_CASE("printer link: a descriptor released is not closed again", "[serial][printer_link]") {
  const std::string path = gctest::temp_dir() + "/printer_link_release";
  PseudoTerminal printer(path);
  const PortOptions options{250000, false};
  int fd = open_serial_port(path, options);
  {
    PortLink link(path, options, fd);
    link.release();  // the session took the descriptor over
    CHECK(link.fd() == -1);
  }
  CHECK(test_printer_link::is_open(fd));
  ::close(fd);
}
