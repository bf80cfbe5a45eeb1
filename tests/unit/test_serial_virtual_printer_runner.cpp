// gc-virtual-printer's run (serial/virtual_printer_runner.hpp): the printer
// answers on the pty its symlink names, logs what it executes, ends when the
// model drops the link and removes the symlink; its statistics line names
// every count.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "gcode/serial/port.hpp"
#include "gcode/serial/virtual_printer_runner.hpp"
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

TEST_CASE("virtual printer run: the statistics line", "[serial][virtual_printer_runner]") {
  VirtualPrinter printer(VirtualPrinterConfig{});
  CHECK(virtual_printer_summary(printer, false) ==
        "executed 0, accepted lines 0, checksum errors 0, line number errors 0, overrun bytes 0, planner starved "
        "0.00 %");
  CHECK(virtual_printer_summary(printer, true).ends_with("0.00 %, link dropped"));
}
