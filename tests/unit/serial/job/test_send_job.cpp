// One run of gc-send (serial/send_job.hpp) says how it ended as a value,
// and its messages go out through the Diagnostics it is given, under that
// tool's name: the library knows no tool and no exit status.
#include <catch2/catch.hpp>

#include <memory>
#include <string>

#include "capture.hpp"
#include "gcode/core/diagnostics.hpp"
#include "gcode/serial/job/send_job.hpp"
#include "gcode/serial/sim/virtual_printer_link.hpp"
#include "test_support.hpp"

using gcode::Diagnostics;
using gcode::serial::SendEnd;
using gcode::serial::SendJob;
using gcode::serial::SendOutcome;

namespace {

// The virtual printer, fast: the print takes no wall time to speak of.
SendJob fast_job(const std::string& file) {
  SendJob job;
  job.file = file;
  gcode::serial::VirtualPrinterConfig config;
  config.time_scale = 50;
  config.instant_moves = true;
  job.link = [config](gcode::serial::EventLoop& loop, double, Diagnostics&) {
    return std::make_unique<gcode::serial::VirtualPrinterLink>(loop, config);
  };
  return job;
}

}  // namespace

TEST_CASE("send job: a print to its end is Finished, its summary under the caller's name", "[serial][send_job]") {
  const std::string file = gctest::temp_dir() + "/part.gcode";
  gctest::write_file(file, ";LAYER:0\nG28\nG1 Z0.2 F600\nG1 X10 Y10 E1 F1200\n;LAYER:1\nG1 Z0.4\nG1 X20 E2\n");
  SendJob job = fast_job(file);
  SendOutcome outcome;
  std::string err = gctest::stderr_of([&] {
    Diagnostics diag("gc-test");
    outcome = gcode::serial::run_send_job(job, diag);
  });
  CHECK(outcome.end == SendEnd::Finished);
  CHECK(outcome.reason.empty());
  CHECK(err.rfind("gc-test: summary: lines ", 0) == 0);
  CHECK(err.find("gc-send") == std::string::npos);
}

TEST_CASE("send job: a line the firmware cannot take is Failed with the reason, also said", "[serial][send_job]") {
  const std::string file = gctest::temp_dir() + "/junk.gcode";
  gctest::write_file(file, "G28\nG1 X10\x01 Y10\nG1 X20\n");
  SendJob job = fast_job(file);
  job.quiet = true;
  SendOutcome outcome;
  std::string err = gctest::stderr_of([&] {
    Diagnostics diag("gc-test", -1);
    outcome = gcode::serial::run_send_job(job, diag);
  });
  CHECK(outcome.end == SendEnd::Failed);
  REQUIRE_FALSE(outcome.reason.empty());
  CHECK(err == "gc-test: " + outcome.reason + "\n");
}

TEST_CASE("send job: a resume without a journal is Refused before anything is sent", "[serial][send_job]") {
  const std::string dir = gctest::temp_dir();
  const std::string file = dir + "/part.gcode";
  gctest::write_file(file, "G28\nG1 X10\n");
  SendJob job = fast_job(file);
  job.resume = true;
  job.journal_path = dir + "/none.journal";
  SendOutcome outcome;
  std::string err = gctest::stderr_of([&] {
    Diagnostics diag("gc-test");
    outcome = gcode::serial::run_send_job(job, diag);
  });
  CHECK(outcome.end == SendEnd::Refused);
  CHECK(outcome.reason.rfind("cannot resume: ", 0) == 0);
  CHECK(err == "gc-test: " + outcome.reason + "\n");
}
