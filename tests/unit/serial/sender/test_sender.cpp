// The host protocol (gcode/serial/sender/sender.hpp) against the Marlin model
// (virtual_printer.hpp) in simulated time, without any I/O: deterministic,
// and an hour of simulated printing costs milliseconds.
//
// The invariant: the commands the printer executed, in order, are exactly the
// commands of the input (plus the final M400): nothing lost, nothing
// duplicated, nothing reordered, whatever the flow mode and the faults.
#include <catch2/catch.hpp>

#include <algorithm>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "gcode/core/firmware.hpp"
#include "gcode/serial/protocol/protocol.hpp"
#include "gcode/serial/sender/sender.hpp"
#include "gcode/serial/sim/virtual_printer.hpp"
#include "printer_talk.hpp"
#include "serial_check.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

namespace {

std::vector<std::string> fixture_commands(const std::string& name, std::size_t limit) {
  std::vector<std::string> out;
  for (auto& c : gctest::commands_of(gctest::read_file(gctest::fixture_path(name)), limit)) out.push_back(c.text);
  return out;
}

struct Outcome {
  SenderState state;
  std::string failure;
  std::vector<std::string> executed;  // numbered commands, in the order executed
  std::vector<long long> numbers;
  VirtualPrinterStats printer;
  SenderStats sender;
  Position last_acked;
  std::string flavour;  // the firmware description the sender ended with
  double seconds = 0;  // simulated
  std::size_t own_lines = 0;  // the sender's own M105s and pace probes the printer ran
};

// Sender and printer connected back to back; the host reacts instantly.
Outcome simulate(const std::vector<std::string>& commands, SenderConfig sc, VirtualPrinterConfig pc,
                 double limit = 1e6, double emergency_at = -1) {
  char* buffer = nullptr;
  std::size_t size = 0;
  std::FILE* log = open_memstream(&buffer, &size);
  Outcome o;
  {
    VirtualPrinter printer(pc, log);
    sc.link_bytes_per_second = pc.baud / 10;
    Sender sender(sc, [](LogLevel, std::uint64_t, std::string_view m) {
      if (std::getenv("GC_TRACE") != nullptr) std::fprintf(stderr, "%.*s\n", static_cast<int>(m.size()), m.data());
    });
    sender.set_trace(std::getenv("GC_TRACE") != nullptr);
    double t = 0;
    std::size_t next = 0;
    std::string rx;
    bool link_down = false;
    sender.start(t);
    while (!sender.finished() && t < limit) {
      while (sender.wants_input() && next < commands.size()) {
        sender.submit(commands[next], next + 1, 1);
        ++next;
      }
      if (next == commands.size()) sender.end_of_input();
      if (emergency_at >= 0 && t >= emergency_at && !sender.emergency()) sender.emergency_stop();
      sender.pump(t);
      std::string_view out = sender.output();
      if (!out.empty()) {
        printer.receive(out, t);
        sender.written(out.size(), t);
      }
      printer.advance(t);
      // The printer's link drops (a scheduled fault) as a port that fails
      // and comes back at once: gc-send --reconnect's session.
      if (printer.link_down() != link_down) {
        link_down = printer.link_down();
        if (link_down) sender.link_lost(t);
        else sender.link_back(t);
      }
      std::string_view tx = printer.transmitted(t);
      rx.append(tx);
      printer.take(tx.size());
      std::size_t pos = 0;
      for (std::size_t nl; (nl = rx.find('\n', pos)) != std::string::npos; pos = nl + 1)
        sender.on_line(std::string_view(rx).substr(pos, nl - pos), t);
      rx.erase(0, pos);
      if (!sender.output().empty() || sender.finished()) continue;
      if (sender.deadline() <= t) {
        sender.on_timer(t);
        if (!sender.output().empty()) continue;
      }
      double next_t = std::min(printer.next_event(), sender.deadline());
      if (next_t <= t) next_t = t + 1e-6;
      t = next_t;
      if (sender.deadline() <= t) sender.on_timer(t);
    }
    o.state = sender.state();
    o.failure = sender.failure();
    o.printer = printer.stats();
    o.sender = sender.stats();
    o.last_acked = sender.last_acknowledged();
    o.flavour = std::string(sender.flavour().name);
    o.seconds = t;
  }
  std::fclose(log);
  std::string text(buffer, size);
  std::free(buffer);
  gctest::ExecutedLog executed = gctest::parse_executed_log(text);
  std::vector<std::string> expected = commands;
  expected.emplace_back("M400");
  o.own_lines = gctest::drop_own_lines(executed, expected);
  o.numbers = executed.numbers;
  o.executed = executed.commands;
  return o;
}

void require_exact(const Outcome& o, const std::vector<std::string>& commands) {
  INFO("failure: " << o.failure << "; simulated seconds " << o.seconds << "; executed " << o.executed.size());
  REQUIRE(o.state == SenderState::Done);
  std::vector<std::string> expected = commands;
  expected.emplace_back("M400");
  for (std::size_t i = 0; i < expected.size() && i < o.executed.size(); ++i) {
    INFO("command " << i);
    REQUIRE(o.executed[i] == expected[i]);
  }
  REQUIRE(o.executed.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    INFO("command " << i);
    REQUIRE(o.executed[i] == expected[i]);
  }
  REQUIRE(gctest::numbers_rise(o.numbers));
}

}  // namespace

TEST_CASE("sender: every flow mode delivers every command once, in order, without overrun", "[serial]") {
  auto commands = fixture_commands("prusa_cube_0.2_mk3s_rel_zhop.gcode", 6000);
  REQUIRE(commands.size() == 6000);
  for (double baud : {250000.0, 115200.0}) {
    for (FlowMode mode : {FlowMode::PingPong, FlowMode::Window, FlowMode::AdvancedOk, FlowMode::Auto}) {
      SenderConfig sc;
      sc.flow = mode;
      VirtualPrinterConfig pc;
      pc.baud = baud;
      pc.advanced_ok = mode != FlowMode::Window;
      pc.heat_rate = 1000;
      INFO(flow_mode_name(mode) << " at " << baud);
      Outcome o = simulate(commands, sc, pc);
      require_exact(o, commands);
      CHECK(o.printer.overrun_bytes == 0);
      CHECK(o.printer.checksum_errors == 0);
      CHECK(o.sender.resend_requests == 0);
      CHECK(o.sender.timeouts == 0);
    }
  }
}

TEST_CASE("sender: window keeps the link busier than ping-pong on a link-bound printer", "[serial]") {
  auto commands = fixture_commands("cura_cube_0.2_abs_zhop_skirt.gcode", 3000);
  VirtualPrinterConfig pc;
  pc.instant_moves = true;
  pc.heat_rate = 1e6;
  SenderConfig ping;
  ping.flow = FlowMode::PingPong;
  SenderConfig window;
  window.flow = FlowMode::Window;
  Outcome a = simulate(commands, ping, pc);
  Outcome b = simulate(commands, window, pc);
  require_exact(a, commands);
  require_exact(b, commands);
  // Simulated time, so this is deterministic: ping-pong waits a round trip per line.
  CHECK(b.seconds < a.seconds * 0.95);
}

TEST_CASE("sender: 20000 lines with corrupted lines, lost oks, busy stalls, spurious resends and garbage", "[serial]") {
  auto commands = fixture_commands("cura_vase_0.2_spiralize.gcode", 20000);
  REQUIRE(commands.size() == 20000);
  for (FlowMode mode : {FlowMode::Window, FlowMode::AdvancedOk, FlowMode::PingPong}) {
    SenderConfig sc;
    sc.flow = mode;
    sc.timeout = 3;
    VirtualPrinterConfig pc;
    pc.advanced_ok = mode == FlowMode::AdvancedOk;
    pc.heat_rate = 1000;
    pc.corrupt = 0.01;
    pc.drop_ok = 0.005;
    pc.busy = 0.001;
    pc.resend = 0.002;
    pc.garbage = 0.002;
    pc.seed = 7;
    INFO(flow_mode_name(mode));
    Outcome o = simulate(commands, sc, pc);
    require_exact(o, commands);
    CHECK(o.printer.corrupted > 100);
    CHECK(o.printer.dropped_oks > 50);
    CHECK(o.printer.spurious_resends > 10);
    CHECK(o.sender.resend_requests > 100);
  }
}

TEST_CASE("sender: a printer that stops answering ends in failure naming the last acknowledged line", "[serial]") {
  auto commands = fixture_commands("cura_cube_0.2_abs_zhop_skirt.gcode", 3000);
  SenderConfig sc;
  sc.timeout = 2;
  sc.max_timeouts = 3;
  VirtualPrinterConfig pc;
  pc.heat_rate = 1000;
  pc.silent_after = 1500;
  Outcome o = simulate(commands, sc, pc);
  REQUIRE(o.state == SenderState::Failed);
  CHECK(o.failure.find("stopped answering") != std::string::npos);
  REQUIRE_FALSE(o.numbers.empty());
  // The last executed line's ok went out before the printer fell silent.
  CHECK(o.last_acked.number == o.numbers.back());
  CHECK(o.failure.find("line " + std::to_string(o.last_acked.source_line) + " of the input") != std::string::npos);
  CHECK(o.sender.timeouts == 4);
}

TEST_CASE("sender: lost oks alone are recovered by M105, the printer keeps printing", "[serial]") {
  auto commands = fixture_commands("slic3r_cube_0.2_abs_reprap_skirt.gcode", 4000);
  SenderConfig sc;
  sc.flow = FlowMode::PingPong;
  sc.timeout = 3;  // above Marlin's 2 s busy keepalive
  VirtualPrinterConfig pc;
  pc.heat_rate = 1000;
  pc.drop_ok = 0.01;
  Outcome o = simulate(commands, sc, pc);
  require_exact(o, commands);
  // Each lost ok stalls ping-pong, and the sender asks as soon as the answer
  // is overdue, long before the 3 s timeout.
  CHECK(o.sender.probes >= o.printer.dropped_oks);
  CHECK(o.sender.timeouts == 0);
}

TEST_CASE("sender: faults on a link-bound printer cost well under twice the clean time and no timeout", "[serial]") {
  // 3000 pieces of at most 0.2 mm from the middle of a print; moves take no
  // time, so every lost ok or resend shows in the time (simulated, so the
  // figures are exact).
  std::string pieces = gctest::subdivided(
      gctest::read_file(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")), 0.2);
  std::vector<std::string> commands;
  for (auto& c : gctest::commands_of(pieces, 5000)) commands.push_back(c.text);
  commands.erase(commands.begin(), commands.begin() + 2000);
  for (FlowMode mode : {FlowMode::Window, FlowMode::AdvancedOk, FlowMode::PingPong}) {
    SenderConfig sc;
    sc.flow = mode;
    VirtualPrinterConfig pc;
    pc.advanced_ok = mode == FlowMode::AdvancedOk;
    pc.instant_moves = true;
    pc.heat_rate = 1e6;
    Outcome clean = simulate(commands, sc, pc);
    require_exact(clean, commands);
    CHECK(clean.sender.probes == 0);
    pc.corrupt = 0.01;
    pc.drop_ok = 0.002;
    pc.resend = 0.002;
    pc.garbage = 0.002;
    pc.seed = 3;
    Outcome faulty = simulate(commands, sc, pc);
    INFO(flow_mode_name(mode) << ": clean " << clean.seconds << " s, faulty " << faulty.seconds << " s");
    require_exact(faulty, commands);
    CHECK(faulty.printer.corrupted >= 20);
    CHECK(faulty.printer.dropped_oks >= 3);
    CHECK(faulty.sender.timeouts == 0);
    CHECK(faulty.seconds < 1.6 * clean.seconds);
  }
}

TEST_CASE("sender: a fatal printer error stops the print", "[serial]") {
  auto commands = fixture_commands("cura_cube_0.2_abs_zhop_skirt.gcode", 2000);
  SenderConfig sc;
  VirtualPrinterConfig pc;
  pc.heat_rate = 1000;
  pc.halt_after = 700;
  Outcome o = simulate(commands, sc, pc);
  REQUIRE(o.state == SenderState::Failed);
  CHECK(o.failure.find("fatal error: Thermal Runaway") != std::string::npos);
  CHECK(o.executed.size() < 700);
}

TEST_CASE("sender: after a link drop the printer ran on: the probe and M114 find where, every command once, in order",
          "[serial][relink]") {
  auto commands = fixture_commands("cura_cube_0.2_abs_zhop_skirt.gcode", 2000);
  for (const char* flow : {"window", "advanced-ok"}) {
    for (const char* fault : {"drop=5@line=40", "drop=30@line=700", "drop=0.5@layer=2", "drop=2@time=200"}) {
      INFO(flow << ", " << fault);
      SenderConfig sc;
      sc.flow = *parse_flow_mode(flow);
      sc.pace = true;
      VirtualPrinterConfig pc;
      pc.heat_rate = 1000;
      pc.advanced_ok = std::string(flow) == "advanced-ok";
      pc.scheduled.push_back(parse_scheduled_fault(fault));
      Outcome o = simulate(commands, sc, pc);
      CHECK(o.printer.link_drops == 1);
      CHECK(o.sender.errors >= 1);  // the probe's "Line Number is not Last Line Number+1"
      require_exact(o, commands);
    }
  }
}

TEST_CASE("sender: the probe after a reconnect waits out a heating printer that reports its temperatures",
          "[serial][relink]") {
  // M109 takes 18 simulated seconds and reads no line meanwhile; --timeout is 5.
  std::vector<std::string> commands = {"M104 S200", "M109 S200", "G1 X10 E1 F600", "G1 X20 E2", "G1 X30 E3"};
  SenderConfig sc;
  sc.timeout = 5;
  VirtualPrinterConfig pc;
  pc.heat_rate = 10;
  pc.scheduled.push_back(parse_scheduled_fault("drop=1@time=3"));  // while M109 waits
  Outcome o = simulate(commands, sc, pc);
  CHECK(o.printer.link_drops == 1);
  CHECK(o.seconds > 18);
  require_exact(o, commands);
}

TEST_CASE("sender: a printer that restarted while its link was down is brought back, in either greeting form",
          "[serial][relink]") {
  auto commands = fixture_commands("cura_cube_0.2_abs_zhop_skirt.gcode", 2000);
  for (GreetingForm form : {GreetingForm::Start, GreetingForm::NulStart}) {
    SenderConfig sc;
    VirtualPrinterConfig pc;
    pc.heat_rate = 1000;
    pc.greeting = form;
    pc.scheduled.push_back(parse_scheduled_fault("drop-reset=5@line=700"));
    Outcome o = simulate(commands, sc, pc);
    INFO(o.failure);
    REQUIRE(o.state == SenderState::Done);
    CHECK(o.sender.resets == 1);
    // What went again: at most the planner's 16 moves and what was in flight.
    CHECK(o.sender.redone_moves <= 20);
    CHECK(std::find(o.executed.begin(), o.executed.end(), "G28 X Y") != o.executed.end());
    // The print's end ran once, as the input has it.
    REQUIRE(o.executed.size() > commands.size() - 700);
    std::vector<std::string> tail(o.executed.end() - static_cast<std::ptrdiff_t>(commands.size() - 720) - 1,
                                  o.executed.end() - 1);
    CHECK(tail == std::vector<std::string>(commands.begin() + 720, commands.end()));
    CHECK(o.executed.back() == "M400");
  }
}

TEST_CASE("sender: after a reconnect, M114 must show where the last line taken left the printer", "[serial][relink]") {
  auto scripted = [](std::string_view m114) {
    SenderConfig sc;
    sc.handshake = false;
    sc.finish_with_m400 = false;
    auto sender = std::make_unique<Sender>(sc, [](LogLevel, std::uint64_t, std::string_view) {});
    Sender& s = *sender;
    s.start(0);
    for (const char* c : {"G1 X10 F600", "G1 X20", "G1 X30"}) s.submit(c, 1, 1);
    s.end_of_input();
    s.pump(0);
    s.written(s.output().size(), 0);
    s.on_line("ok", 0.1);  // N1; the oks of N2 and N3 are lost with the link
    s.link_lost(0.2);
    CHECK(s.output().empty());
    s.link_back(1.0);
    // A number the printer cannot expect: it names its last line instead.
    CHECK(s.output() == gctest::numbered(5, "M105"));
    s.written(s.output().size(), 1.0);
    s.on_line("Error:Line Number is not Last Line Number+1, Last Line: 2", 1.1);
    s.on_line("Resend: 3", 1.1);
    CHECK(s.output().empty());  // M114 waits for the refusal's ok
    s.on_line("ok", 1.1);
    CHECK(s.output() == "M114\n");
    s.written(s.output().size(), 1.1);
    s.on_line(m114, 1.2);
    return sender;
  };
  auto kept = scripted("X:20.00 Y:0.00 Z:0.00 E:0.00 Count X:1600 Y:0 Z:0");
  CHECK(kept->state() == SenderState::Printing);
  CHECK(kept->last_acknowledged().number == 2);
  kept->on_line("ok", 1.2);
  CHECK(kept->output() == gctest::numbered(3, "G1 X30"));
  auto moved = scripted("X:25.00 Y:0.00 Z:0.00 E:0.00 Count X:2000 Y:0 Z:0");
  CHECK(moved->state() == SenderState::Failed);
  CHECK(moved->failure().find("stands at X25.000, but N2") != std::string::npos);
}

TEST_CASE("sender: a link drop during the handshake asks M110 and M115 again, not where a print stands",
          "[serial][relink]") {
  // Nothing numbered went out yet: the probe's refusal ("Last Line", its
  // "ok") would pass for M115's answer and leave the sender waiting for a
  // relocation that never comes (found with a resumed gc-send whose port
  // dropped right after M115).
  SenderConfig sc;
  sc.finish_with_m400 = false;
  Sender s(sc, [](LogLevel, std::uint64_t, std::string_view) {});
  s.start(0);
  CHECK(s.output() == "M110 N0\n");
  s.written(s.output().size(), 0);
  s.on_line("ok", 0.01);
  CHECK(s.output() == "M115\n");
  s.written(s.output().size(), 0.01);
  s.link_lost(0.02);
  s.link_back(0.5);
  CHECK_FALSE(s.relinking());
  CHECK(s.state() == SenderState::Handshake);
  REQUIRE(s.output() == "M110 N0\n");
  s.written(s.output().size(), 0.5);
  s.on_line("ok", 0.51);
  REQUIRE(s.output() == "M115\n");
  s.written(s.output().size(), 0.51);
  s.on_line("FIRMWARE_NAME:Marlin 2.1.2", 0.52);
  s.on_line("ok", 0.52);
  s.submit("G1 X10 F600", 1, 1);
  s.on_timer(0.7);  // the link quiet a moment after M115
  CHECK(s.state() == SenderState::Printing);
  CHECK(s.output() == gctest::numbered(1, "G1 X10 F600"));
  // A resume numbers on: only M115 is asked, before and after the drop.
  SenderConfig rc;
  rc.handshake = false;
  Sender r(rc, [](LogLevel, std::uint64_t, std::string_view) {});
  r.continue_from(41, gcode::MachineState{});
  r.start(0);
  CHECK(r.output() == "M115\n");
  r.written(r.output().size(), 0);
  r.link_lost(0.02);
  r.link_back(0.5);
  CHECK(r.state() == SenderState::Capabilities);
  CHECK(r.output() == "M115\n");
}

TEST_CASE("sender: a greeting while a resume asks M115 of a printer that kept running is a reset, not a boot",
          "[serial][reset][resume]") {
  // The printer held the print (it took line 40 and ran it); its "start"
  // now means the print is lost from its planner: the way back, numbered
  // on from the print, not M110 N0.
  SenderConfig sc;
  sc.handshake = false;
  Sender s(sc, [](LogLevel, std::uint64_t, std::string_view) {});
  gcode::MachineState at;
  at.position = {50, 60, 0.4, 0};
  at.known = {true, true, true, true};
  gcode::serial::ResumeTrack track;
  track.top_z = 0.4;
  s.continue_from(41, at, track, 120, 2);
  s.start(0);
  REQUIRE(s.output() == "M115\n");
  s.written(s.output().size(), 0);
  s.on_line("start", 0.1);
  INFO(s.failure());
  CHECK(s.stats().resets == 1);
  CHECK(s.state() == SenderState::Handshake);
  CHECK(s.output() == "M110 N40\n");
  // A board that greets twice while it boots: the handshake again, the
  // way back kept.
  s.written(s.output().size(), 0.1);
  s.on_line("start", 0.2);
  CHECK(s.stats().resets == 1);
  CHECK(s.output() == "M110 N40\n");
  // The link drops during that handshake: the printer that reset needs its
  // numbering set again, not M115 alone as the resume began.
  s.written(s.output().size(), 0.2);
  s.link_lost(0.3);
  s.link_back(0.6);
  CHECK(s.state() == SenderState::Handshake);
  CHECK(s.output() == "M110 N40\n");
}

TEST_CASE("sender: M112 goes out at once and halts the printer", "[serial]") {
  auto commands = fixture_commands("cura_cube_0.2_abs_zhop_skirt.gcode", 2000);
  SenderConfig sc;
  VirtualPrinterConfig pc;
  pc.heat_rate = 1000;
  Outcome o = simulate(commands, sc, pc, 1e6, 60.0);
  CHECK(o.state == SenderState::Cancelled);
  CHECK(o.executed.size() < commands.size());
}

TEST_CASE("sender: pacing (no more moves ahead than the planner holds) delivers everything and costs no print time",
          "[serial]") {
  auto commands = fixture_commands("prusa_cube_0.2_mk3s_rel_zhop.gcode", 6000);
  VirtualPrinterConfig pc;
  pc.heat_rate = 1000;
  SenderConfig plain;
  SenderConfig paced;
  paced.pace = true;
  paced.read_ahead = 1;
  Outcome a = simulate(commands, plain, pc);
  Outcome b = simulate(commands, paced, pc);
  require_exact(a, commands);
  require_exact(b, commands);
  // Simulated time with a host that reacts at once: the planner is kept as
  // busy as with the flow control alone.
  CHECK(b.seconds < a.seconds * 1.01);
  CHECK(b.printer.starved <= a.printer.starved + 0.005 * b.seconds);
  CHECK(b.printer.overrun_bytes == 0);
}

TEST_CASE("sender: Marlin variants, a Resend without its ok and wait when idle: exact, no timeout", "[serial][flavour]") {
  auto commands = fixture_commands("prusa_cube_0.2_mk3s_rel_zhop.gcode", 3000);
  VirtualPrinterConfig pc;
  pc.corrupt = 0.02;
  pc.resend_ok = false;  // "Resend: n" and nothing after it
  pc.idle_wait = 1;      // NO_TIMEOUTS: "wait" every second while idle
  pc.heat_rate = 1000;
  Outcome o = simulate(commands, SenderConfig{}, pc);
  require_exact(o, commands);
  CHECK(o.sender.resend_requests > 10);
  CHECK(o.sender.timeouts == 0);
  CHECK(o.flavour == "marlin2");
}

TEST_CASE("sender: Klipper, Prusa and RepRapFirmware detected from M115, every command once, no timeout",
          "[serial][flavour]") {
  auto commands = fixture_commands("prusa_cube_0.2_mk3s_rel_zhop.gcode", 3000);
  for (const char* firmware : {"klipper", "prusa", "rrf"}) {
    INFO(firmware);
    VirtualPrinterConfig pc;
    pc.firmware = firmware;
    pc.heat_rate = 1000;
    pc.report_link = false;
    Outcome o = simulate(commands, SenderConfig{}, pc);
    INFO("overrun bytes " << o.printer.overrun_bytes << ", drained " << o.printer.drained_bytes << ", stray oks "
                          << o.sender.stray_oks);
    require_exact(o, commands);
    CHECK(o.sender.timeouts == 0);
    CHECK(o.flavour == gcode::find_firmware(firmware)->name);
  }
}

TEST_CASE("sender: Prusa's M600 and its own pause wait for the user, no timeout however long", "[serial][flavour]") {
  std::vector<std::string> commands = {"G28", "G1 X10 Y10 F3000", "M600", "G1 X20", "M601", "G1 X30", "G1 X40"};
  VirtualPrinterConfig pc;
  pc.firmware = "prusa";
  pc.user_seconds = 600;  // ten minutes for each
  SenderConfig sc;
  sc.timeout = 2;
  Outcome o = simulate(commands, sc, pc);
  require_exact(o, commands);
  CHECK(o.sender.timeouts == 0);
  CHECK(o.seconds > 1200);
}

TEST_CASE("sender: on Klipper a port that comes back ends the print, saying why", "[serial][flavour]") {
  auto commands = fixture_commands("prusa_cube_0.2_mk3s_rel_zhop.gcode", 400);
  VirtualPrinterConfig pc;
  pc.firmware = "klipper";
  pc.heat_rate = 1000;
  parse_virtual_options("drop=2@line=200", pc);
  Outcome o = simulate(commands, SenderConfig{}, pc);
  CHECK(o.state == SenderState::Failed);
  CHECK(o.failure.find("klipper does not number lines") != std::string::npos);
}

TEST_CASE("sender: OctoPrint's virtual printer (64-byte buffer, a write waits, scripted errors): 3000 moves in 10 s",
          "[serial][flavour]") {
  // Issue 41: paced, it took 46-65 s with 4-6 stalls of ten seconds, each
  // after gc-send had written more than the 64 bytes the printer takes.
  auto commands = fixture_commands("prusa_cube_0.2_mk3s_rel_zhop.gcode", 3000);
  VirtualPrinterConfig pc;
  parse_virtual_options("octoprint,heat-rate=1000", pc);
  for (bool pace : {true, false}) {
    SenderConfig sc;
    sc.rx_buffer = 64;  // --rx-buffer 64: stated, as the printer does not say
    sc.pace = pace;
    sc.read_ahead = 1;
    INFO((pace ? "paced" : "--no-pace"));
    Outcome o = simulate(commands, sc, pc);
    INFO("simulated " << o.seconds << " s, timeouts " << o.sender.timeouts << ", bytes dropped "
                      << o.printer.timed_out_bytes << ", pace probes " << o.sender.pace_probes << ", polls "
                      << o.sender.polls);
    require_exact(o, commands);
    CHECK(o.printer.scripted_errors == 4);
    CHECK(o.printer.overrun_bytes == 0);
    CHECK(o.sender.timeouts == 0);
    CHECK(o.seconds <= 10);
    if (std::getenv("GC_FIGURES") != nullptr)
      std::fprintf(stderr, "octoprint %s: %.3f s simulated, pace probes %llu, polls %llu, resends %llu\n",
                   pace ? "paced" : "unpaced", o.seconds, static_cast<unsigned long long>(o.sender.pace_probes),
                   static_cast<unsigned long long>(o.sender.polls),
                   static_cast<unsigned long long>(o.sender.resend_requests));
  }
}

TEST_CASE("sender: ten times the file's pace, paced as fast as --no-pace, on the printer's own clock", "[serial][pace]") {
  // Issue 41: real Marlin 2.0.7.2 with ADVANCED_OK, paced at gc-send's
  // default flow (window) 65 s against 59 unpaced (134 against 47 on a busy
  // host); with --flow auto, 47. Auto is the default: ADVANCED_OK's P and B
  // where the answers carry them, the window (and pace probes) otherwise.
  auto commands = fixture_commands("prusa_cube_0.2_mk3s_rel_zhop.gcode", 6000);
  for (bool advanced : {true, false}) {
    VirtualPrinterConfig pc;
    pc.heat_rate = 1000;
    pc.speed_factor = 10;
    pc.advanced_ok = advanced;
    double time[2] = {0, 0};
    for (bool pace : {true, false}) {
      SenderConfig sc;
      sc.flow = FlowMode::Auto;
      sc.pace = pace;
      sc.read_ahead = 1;
      INFO((advanced ? "ADVANCED_OK" : "plain Marlin") << (pace ? ", paced" : ", --no-pace"));
      Outcome o = simulate(commands, sc, pc);
      require_exact(o, commands);
      time[pace ? 0 : 1] = o.printer.last_move_end - o.printer.first_move;
      if (std::getenv("GC_FIGURES") != nullptr)
        std::fprintf(stderr, "10x %s %s: motion %.3f s simulated, pace probes %llu, polls %llu\n",
                     advanced ? "advanced-ok" : "plain", pace ? "paced" : "unpaced", time[pace ? 0 : 1],
                     static_cast<unsigned long long>(o.sender.pace_probes),
                     static_cast<unsigned long long>(o.sender.polls));
    }
    INFO((advanced ? "ADVANCED_OK" : "plain Marlin") << ": paced " << time[0] << " s, unpaced " << time[1] << " s");
    CHECK(time[0] <= 1.10 * time[1]);
  }
}

TEST_CASE("sender: Klipper holds a move's ok while a second of motion is queued: no M105 asks about it",
          "[serial][flavour]") {
  // Issue 41: about 1070 "overdue" M105s in one print on real Klipper, which
  // holds an ok while about 1 s of motion is queued (gc-send asked 0.1 s
  // after the last answer).
  auto commands = fixture_commands("prusa_cube_0.2_mk3s_rel_zhop.gcode", 3000);
  VirtualPrinterConfig pc;
  pc.firmware = "klipper";
  pc.heat_rate = 1000;
  pc.report_link = false;
  SenderConfig sc;
  sc.pace = true;
  sc.read_ahead = 1;
  Outcome o = simulate(commands, sc, pc);
  INFO("overdue answers asked " << o.sender.probes << ", polls " << o.sender.polls);
  require_exact(o, commands);
  CHECK(o.sender.probes == 0);
  CHECK(o.sender.timeouts == 0);
}
