// The virtual printer's scheduled faults (gcode/serial/sim/virtual_fault.hpp and
// the reset and link drop of virtual_printer.hpp): what a host finds after a
// board restarted, or after its link was gone while the board ran on, and
// the answers it learns that from (a mis-numbered probe, M114).
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gcode/serial/protocol/printer_report.hpp"
#include "gcode/serial/protocol/protocol.hpp"
#include "gcode/serial/sim/virtual_printer.hpp"
#include "printer_talk.hpp"

using namespace gcode::serial;
using gctest::answers;
using gctest::numbered;

namespace {

// Lines 1..count: 10 mm moves along X at 600 mm/min (1 s each), extruding.
std::string moves(int first, int count) {
  std::string s;
  for (int n = first; n < first + count; ++n) s += numbered(n, "G1 X" + std::to_string(10 * n) + " E" + std::to_string(n) + " F600");
  return s;
}

// The printer's log, in memory.
struct Log {
  char* data = nullptr;
  std::size_t size = 0;
  std::FILE* file = open_memstream(&data, &size);
  ~Log() {
    std::fclose(file);
    std::free(data);
  }
  std::string text() {
    std::fflush(file);
    return std::string(data, size);
  }
};

}  // namespace

TEST_CASE("virtual printer faults parse, with their moments, bad ones are refused", "[serial][virtual_fault]") {
  ScheduledFault f = parse_scheduled_fault("reset@line=120");
  CHECK(f.kind == ScheduledFault::Kind::Reset);
  CHECK(f.trigger == ScheduledFault::Trigger::Line);
  CHECK(f.at == 120);
  f = parse_scheduled_fault("drop=2.5@time=30");
  CHECK(f.kind == ScheduledFault::Kind::Drop);
  CHECK(f.seconds == 2.5);
  CHECK(f.trigger == ScheduledFault::Trigger::Time);
  f = parse_scheduled_fault("drop-reset=4@layer=3");
  CHECK(f.kind == ScheduledFault::Kind::DropReset);
  CHECK(f.trigger == ScheduledFault::Trigger::Layer);
  CHECK(f.at == 3);
  for (const char* bad : {"reset", "reset@", "reset@line", "reset@page=3", "drop@line=3", "drop=x@line=3",
                          "melt@line=3", "reset@line=-1"})
    CHECK_THROWS_AS(parse_scheduled_fault(bad), std::invalid_argument);
  VirtualPrinterConfig c;
  parse_virtual_options("time-scale=10,reset@line=5,drop=3@time=2,greeting=twice", c);
  REQUIRE(c.scheduled.size() == 2);
  CHECK(c.scheduled[1].kind == ScheduledFault::Kind::Drop);
  CHECK(c.greeting == GreetingForm::Twice);
  CHECK_THROWS_AS(parse_virtual_options("greeting=hello", c), std::invalid_argument);
}

TEST_CASE("virtual printer: a mis-numbered probe names the last line, M114 the position, as Marlin",
          "[serial][virtual_fault]") {
  VirtualPrinter p(VirtualPrinterConfig{});
  answers(p, 1);
  p.receive("M110 N0\n" + moves(1, 3), 1);
  answers(p, 5);
  p.receive(numbered(999, "M105") + "M114\n", 5);
  std::vector<std::string> a = answers(p, 6);
  REQUIRE(a.size() == 5);
  CHECK(a[0] == "Error:Line Number is not Last Line Number+1, Last Line: 3");
  CHECK(a[1] == "Resend: 4");
  CHECK(last_line_of(a[0]) == 3);
  CHECK(a[3] == "X:30.00 Y:0.00 Z:0.00 E:3.00 Count X:2400 Y:0 Z:0");
  std::optional<PositionReport> at = parse_position_report(a[3]);
  REQUIRE(at);
  CHECK(at->axis[0] == 30);
  CHECK(at->axis[3] == 3);
}

TEST_CASE("virtual printer: a reset loses queue, planner, position, homing, heaters and line numbers, and greets",
          "[serial][virtual_fault]") {
  Log log;
  VirtualPrinterConfig c;
  c.scheduled.push_back(parse_scheduled_fault("reset@line=6"));
  VirtualPrinter p(c, log.file);
  answers(p, 0.5);
  p.receive("M110 N0\n" + numbered(1, "M104 S210") + numbered(2, "G28") + moves(3, 8), 0.5);
  // G28 takes 3 s, then line 3 starts: 6 has left the queue at once (the
  // planner has room), the reset comes right after it.
  std::vector<std::string> a = answers(p, 4);
  CHECK(p.stats().resets == 1);
  CHECK(a.back() == "start");
  CHECK_FALSE(p.homed());
  p.receive("M105\nM114\n" + numbered(7, "G90"), 4);
  a = answers(p, 5);
  REQUIRE(a.size() == 6);
  CHECK(a[0].find("/0.00") != std::string::npos);  // the hot end's target is gone
  CHECK(a[1].rfind("X:0.00 Y:0.00 Z:0.00 E:0.00", 0) == 0);
  CHECK(a[3] == "Error:Line Number is not Last Line Number+1, Last Line: 0");
  p.receive(numbered(1, "G90"), 5);
  CHECK(answers(p, 6) == std::vector<std::string>{"ok"});
  // The log names what never ran: 3..6 were planned (logged as they left
  // the queue), 7 and 8 were queued (the rest overran the RX buffer while
  // G28 blocked).
  std::string text = log.text();
  CHECK(text.find("\tG1 X60 E6 F600\n") != std::string::npos);
  CHECK(text.find("\tG1 X70") == std::string::npos);
  CHECK(text.find("# reset at ") != std::string::npos);
  INFO(text);
  CHECK(text.find("lost from the planner and queue N3 N4 N5 N6; N7 N8\n") != std::string::npos);
}

TEST_CASE("virtual printer: the greeting of a reset in each form", "[serial][virtual_fault]") {
  auto greeting = [](GreetingForm form) {
    VirtualPrinterConfig c;
    c.greeting = form;
    VirtualPrinter p(c);
    answers(p, 1);
    p.reset(1);
    return answers(p, 2);
  };
  CHECK(greeting(GreetingForm::Start) == std::vector<std::string>{"start"});
  CHECK(greeting(GreetingForm::NulStart) == std::vector<std::string>{std::string("\0start", 6)});
  CHECK(greeting(GreetingForm::Twice) == std::vector<std::string>{"start", "start"});
  std::vector<std::string> external = greeting(GreetingForm::ExternalReset);
  REQUIRE(external.size() == 3);
  CHECK(external[0] == "start");
  CHECK(external[1] == "echo: External Reset");
  // The line sent last ("start", the boot greeting of the first answers
  // call), cut to its first half ("sta"), the greeting straight after.
  CHECK(greeting(GreetingForm::CutLine) == std::vector<std::string>{"stastart"});
}

TEST_CASE("virtual printer: a reset cuts the ok it was sending", "[serial][virtual_fault]") {
  VirtualPrinterConfig c;
  c.greeting = GreetingForm::CutLine;
  c.advanced_ok = true;
  VirtualPrinter p(c);
  answers(p, 0.5);
  p.receive("M110 N0\n", 0.5);
  std::vector<std::string> ok = answers(p, 1);
  REQUIRE(ok.size() == 1);
  INFO(ok[0]);
  REQUIRE(ok[0].rfind("ok P", 0) == 0);
  p.reset(1);
  CHECK(answers(p, 2) == std::vector<std::string>{ok[0].substr(0, (ok[0].size() + 1) / 2) + "start"});
}

TEST_CASE("virtual printer: during a link drop the board runs on, silent, afterwards it expects the next line",
          "[serial][virtual_fault]") {
  Log log;
  VirtualPrinterConfig c;
  c.scheduled.push_back(parse_scheduled_fault("drop=20@time=0.7"));
  VirtualPrinter p(c, log.file);
  answers(p, 0.5);
  p.receive("M110 N0\n" + moves(1, 6), 0.5);
  // All six moves are in the planner (6 s of motion) when the link goes.
  std::vector<std::string> a = answers(p, 0.6);
  CHECK(a == std::vector<std::string>(7, "ok"));
  answers(p, 0.8);
  CHECK(p.link_down());
  p.receive(numbered(7, "G1 X70 F600"), 1);  // lost on a link that is not there
  CHECK(answers(p, 20).empty());
  CHECK(p.link_down());
  // The six 1 s moves ran meanwhile.
  a = answers(p, 21);
  CHECK_FALSE(p.link_down());
  CHECK(a.empty());  // no greeting: it did not restart
  CHECK(p.stats().executed == 7);
  p.receive(numbered(999, "M105") + "M114\n", 21);
  a = answers(p, 22);
  REQUIRE(a.size() == 5);
  CHECK(last_line_of(a[0]) == 6);
  CHECK(a[3].rfind("X:60.00 Y:0.00 Z:0.00 E:6.00", 0) == 0);
  std::string text = log.text();
  CHECK(text.find("# link down at ") != std::string::npos);
  CHECK(text.find("# link up at ") != std::string::npos);
  CHECK(text.find("\tG1 X60 E6 F600\n") != std::string::npos);
}

TEST_CASE("virtual printer: a drop with a reset greets when the link returns, its queue lost",
          "[serial][virtual_fault]") {
  VirtualPrinterConfig c;
  c.queue = 2;
  c.planner = 2;
  c.scheduled.push_back(parse_scheduled_fault("drop-reset=3@line=1"));
  VirtualPrinter p(c);
  answers(p, 0.5);
  p.receive("M110 N0\n" + moves(1, 8), 0.5);
  answers(p, 1);
  CHECK(p.link_down());
  std::vector<std::string> a = answers(p, 4);
  CHECK(a == std::vector<std::string>{"start"});
  CHECK(p.stats().resets == 1);
  // Line 1 went to the planner as it arrived; the lines still on the wire
  // when the link went were lost, and the reset lost the planned move.
  CHECK(p.stats().executed == 2);
  CHECK(p.stats().link_drops == 1);
  p.receive(numbered(999, "M105"), 4);
  a = answers(p, 5);
  REQUIRE_FALSE(a.empty());
  CHECK(last_line_of(a[0]) == 0);
}

TEST_CASE("virtual printer: faults at a simulated time and at a layer", "[serial][virtual_fault]") {
  VirtualPrinterConfig c;
  c.scheduled.push_back(parse_scheduled_fault("reset@time=2.5"));
  VirtualPrinter p(c);
  answers(p, 0.5);
  p.receive("M110 N0\n" + moves(1, 2) + numbered(3, "G4 S10"), 0.5);
  CHECK(p.stats().resets == 0);
  answers(p, 2.4);
  CHECK(p.stats().resets == 0);
  CHECK(answers(p, 2.6) == std::vector<std::string>{"start"});

  VirtualPrinterConfig l;
  l.scheduled.push_back(parse_scheduled_fault("reset@layer=2"));
  Log log;
  VirtualPrinter q(l, log.file);
  answers(q, 0.5);
  // Layer 1 at Z0.2 (a travel first, a lift that is not a layer), layer 2 at Z0.4.
  q.receive("M110 N0\n" + numbered(1, "G1 Z0.2 F600") + numbered(2, "G1 X5 E1 F600") + numbered(3, "G1 Z1 F600") +
                numbered(4, "G1 Z0.4 F600") + numbered(5, "G1 X0 E2 F600") + numbered(6, "G1 X5 E3 F600"),
            0.5);
  answers(q, 30);
  CHECK(q.layer() == 2);
  CHECK(q.stats().resets == 1);
  std::string text = log.text();
  CHECK(text.find("\tG1 X0 E2 F600\n") != std::string::npos);
  CHECK(text.find("\tG1 X5 E3 F600\n") == std::string::npos);
}

TEST_CASE("virtual fault: a link outage lasts its seconds and says whether the board restarts",
          "[serial][virtual_fault]") {
  LinkOutage outage;
  CHECK_FALSE(outage.down());
  CHECK(outage.up_at() == std::numeric_limits<double>::infinity());
  outage.begin(30, 5, false);
  CHECK(outage.down());
  CHECK(outage.up_at() == 35);
  CHECK_FALSE(outage.end());  // drop: the board ran on
  CHECK_FALSE(outage.down());
  CHECK(outage.up_at() == std::numeric_limits<double>::infinity());
  outage.begin(40, 2, true);
  CHECK(outage.end());  // drop-reset: it restarts as the link comes back
  CHECK_FALSE(outage.end());
}
