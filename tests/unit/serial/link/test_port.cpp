// Serial ports and pseudo-terminals (serial/port.hpp): a PseudoTerminal is
// reachable through its link (gone with it); open_serial_port opens it like
// a printer's port, non-blocking, raw both ways (no CR/LF translation, no
// echo, an empty port is EAGAIN and not end of file); what is no serial
// port is refused with a readable message.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "gcode/serial/link/port.hpp"
#include "test_support.hpp"

using gcode::serial::PseudoTerminal;

namespace {

// Reads what arrives on `fd` within `ms`, until `want` bytes.
std::string read_within(int fd, std::size_t want, int ms = 2000) {
  std::string out;
  while (out.size() < want) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, ms) <= 0) break;
    char b[256];
    ssize_t n = ::read(fd, b, sizeof b);
    if (n <= 0) break;
    out.append(b, static_cast<std::size_t>(n));
  }
  return out;
}

}  // namespace

TEST_CASE("port: a pseudo-terminal is reachable through its link, removed with it", "[serial][port]") {
  std::string link = gctest::temp_dir() + "/printer";
  gctest::write_file(link, "a stale file in the way");
  {
    PseudoTerminal pty(link);
    CHECK(pty.master() >= 0);
    CHECK(pty.slave_path().rfind("/dev/pts/", 0) == 0);
    CHECK(std::filesystem::is_symlink(link));
    CHECK(std::filesystem::read_symlink(link).string() == pty.slave_path());
  }
  CHECK_FALSE(std::filesystem::exists(std::filesystem::symlink_status(link)));
  CHECK_THROWS_WITH(PseudoTerminal(gctest::temp_dir() + "/no/such/dir/printer"),
                    Catch::StartsWith("cannot create the link "));
}

TEST_CASE("port: open_serial_port on a pty: non-blocking, raw both ways", "[serial][port]") {
  std::string link = gctest::temp_dir() + "/printer";
  PseudoTerminal pty(link);
  int fd = gcode::serial::open_serial_port(link, gcode::serial::PortOptions{.baud = 250000, .reset = false});
  REQUIRE(fd >= 0);
  CHECK((::fcntl(fd, F_GETFL) & O_NONBLOCK) != 0);
  CHECK(gcode::serial::is_pseudo_terminal(fd));
  CHECK_FALSE(gcode::serial::is_pseudo_terminal(pty.master()));  // the master is /dev/ptmx
  char b[8];
  CHECK(::read(fd, b, sizeof b) == -1);  // nothing yet: EAGAIN, not end of file
  CHECK(errno == EAGAIN);
  // Host to printer: no "\n" -> "\r\n", no echo back.
  const std::string line = "N1 G28*18\n";
  REQUIRE(::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size()));
  CHECK(read_within(pty.master(), line.size()) == line);
  CHECK(read_within(fd, 1, 50).empty());
  // Printer to host: "\r\n" arrives as sent (no CR -> LF).
  const std::string answer = "ok\r\nT:20.0 /0.0\r\n";
  REQUIRE(::write(pty.master(), answer.data(), answer.size()) == static_cast<ssize_t>(answer.size()));
  CHECK(read_within(fd, answer.size()) == answer);
  ::close(fd);
}

TEST_CASE("port: what is no serial port is refused", "[serial][port]") {
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/file";
  gctest::write_file(file, "G28\n");
  CHECK_THROWS_WITH(gcode::serial::open_serial_port(file, {}), Catch::StartsWith(file + " is not a serial port: "));
  CHECK_THROWS_WITH(gcode::serial::open_serial_port(dir + "/ttyACM9", {}),
                    "cannot open " + dir + "/ttyACM9: No such file or directory");
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  CHECK_FALSE(gcode::serial::is_pseudo_terminal(fds[0]));
  ::close(fds[0]);
  ::close(fds[1]);
  CHECK_FALSE(gcode::serial::is_pseudo_terminal(-1));
}

TEST_CASE("port: candidate ports come sorted by path", "[serial][port]") {
  auto ports = gcode::serial::list_serial_ports();  // none on a build machine, usually
  CHECK(std::is_sorted(ports.begin(), ports.end(), [](const auto& a, const auto& b) { return a.path < b.path; }));
  for (const auto& p : ports) CHECK(p.path.rfind("/dev/", 0) == 0);
}

TEST_CASE("port: a pseudo-terminal that cannot make its link closes what it opened", "[serial][port]") {
  auto open_fds = [] {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) ++n;
    return n;
  };
  const std::size_t before = open_fds();
  const std::string link = gctest::temp_dir() + "/no-such-folder/printer";
  for (int i = 0; i < 3; ++i)
    CHECK_THROWS_WITH(gcode::serial::PseudoTerminal(link), Catch::Contains("cannot create the link"));
  CHECK(open_fds() == before);
}
