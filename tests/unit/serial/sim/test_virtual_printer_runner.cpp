// gc-virtual-printer's run (serial/virtual_printer_runner.hpp): the printer
// answers on the pty its symlink names, logs what it executes, ends when the
// model drops the link and removes the symlink; its statistics line names
// every count.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "gcode/serial/link/port.hpp"
#include "gcode/serial/sim/virtual_printer_runner.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

TEST_CASE("virtual printer run: serves its link until the model drops it, then removes the link",
          "[serial][virtual_printer_runner]") {
  const std::string dir = gctest::temp_dir();
  VirtualPrinterRun run{.link = dir + "/printer", .log = dir + "/log.tsv", .quiet = true};
  VirtualPrinterConfig c;
  c.time_scale = 100;
  c.disconnect_after = 1;
  int status = -1;
  std::thread printer([&] { status = run_virtual_printer(run, c); });
  for (int i = 0; i < 500 && !std::filesystem::is_symlink(run.link); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  REQUIRE(std::filesystem::is_symlink(run.link));
  int fd = open_serial_port(run.link, PortOptions{});
  const std::string line = "G90\n";
  REQUIRE(::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size()));
  printer.join();  // the disconnect fault after one command ends the run
  ::close(fd);
  CHECK(status == 0);
  CHECK_FALSE(std::filesystem::exists(std::filesystem::symlink_status(run.link)));
  CHECK(gctest::read_file(run.log).find("G90") != std::string::npos);
}

TEST_CASE("virtual printer run: a link drop removes the pty's path and brings a new pty back there",
          "[serial][virtual_printer_runner]") {
  const std::string dir = gctest::temp_dir();
  VirtualPrinterRun run{.link = dir + "/printer", .log = dir + "/log.tsv", .quiet = true};
  VirtualPrinterConfig c;
  c.time_scale = 10;
  c.scheduled.push_back(parse_scheduled_fault("drop=5@line=1"));  // half a second of wall time
  c.disconnect_after = 2;
  int status = -1;
  std::thread printer([&] { status = run_virtual_printer(run, c); });
  namespace fs = std::filesystem;
  auto wait_for = [&](bool present) {
    for (int i = 0; i < 500 && fs::exists(fs::symlink_status(run.link)) != present; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return fs::exists(fs::symlink_status(run.link)) == present;
  };
  REQUIRE(wait_for(true));
  std::string first_pty = fs::read_symlink(run.link).string();
  int fd = open_serial_port(run.link, PortOptions{});
  const std::string line = "N1 G90*17\n";
  REQUIRE(::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size()));
  auto dropped_at = std::chrono::steady_clock::now();
  REQUIRE(wait_for(false));  // the path is gone, as a USB device's
  // The host's descriptor hangs up: end of file or EIO, never a blocked read.
  char buf[256];
  ssize_t n = 0;
  for (int i = 0; i < 200 && (n = ::read(fd, buf, sizeof buf)) > 0; ++i) {
  }
  CHECK(n <= 0);
  CHECK((n == 0 || errno == EIO));
  ::close(fd);
  REQUIRE(wait_for(true));
  double gone = std::chrono::duration<double>(std::chrono::steady_clock::now() - dropped_at).count();
  CHECK(gone > 0.4);
  CHECK(gone < 2.0);
  fd = open_serial_port(run.link, PortOptions{});
  const std::string probe = "M114\n";
  REQUIRE(::write(fd, probe.data(), probe.size()) == static_cast<ssize_t>(probe.size()));
  printer.join();  // the second command ends the run (disconnect-after=2)
  ::close(fd);
  CHECK(status == 0);
  std::string log = gctest::read_file(run.log);
  CHECK(log.find("# link down at ") != std::string::npos);
  CHECK(log.find("# link up at ") != std::string::npos);
  CHECK(log.find("M114") != std::string::npos);
  CHECK_FALSE(first_pty.empty());
}

TEST_CASE("virtual printer run: the statistics line", "[serial][virtual_printer_runner]") {
  VirtualPrinter printer(VirtualPrinterConfig{});
  CHECK(virtual_printer_summary(printer, false) ==
        "executed 0, accepted lines 0, checksum errors 0, line number errors 0, overrun bytes 0, planner starved "
        "0.00 %");
  CHECK(virtual_printer_summary(printer, true).ends_with("0.00 %, link dropped"));
  printer.reset(0);
  CHECK(virtual_printer_summary(printer, false).ends_with("0.00 %, resets 1, link drops 0"));
}
