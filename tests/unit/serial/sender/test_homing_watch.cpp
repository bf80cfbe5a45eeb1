// A printer whose homing failed or was lost (homing_watch.hpp): the watch
// on its own, then the sender that stops the print: nothing more of the
// file goes out, what the handler sends as its safe end does, and the
// print fails with the reason.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/serial/protocol/protocol.hpp"
#include "gcode/serial/sender/homing_watch.hpp"
#include "gcode/serial/sender/sender.hpp"

using gcode::Line;
using namespace gcode::serial;

namespace {

using Lines = std::vector<std::string>;

// Window flow, no handshake, a link without byte time (as the replay tests).
SenderConfig homing_config() {
  SenderConfig c;
  c.flow = FlowMode::Window;
  c.handshake = false;
  c.link_bytes_per_second = 0;
  c.timeout = 10;
  return c;
}

struct Run {
  Run() : sender(homing_config(), [this](LogLevel level, std::uint64_t, std::string_view m) {
            if (level != LogLevel::Trace) messages.emplace_back(m);
          }) {
    sender.start(0);
  }
  void input(const Lines& commands) {
    for (const std::string& c : commands) sender.submit(c, ++line, 1);
    sender.end_of_input();
  }
  // The commands (without number and checksum) that went out since the last call.
  Lines sent() {
    sender.pump(now);
    Lines out;
    std::string_view o = sender.output();
    for (std::size_t pos = 0, nl; (nl = o.find('\n', pos)) != std::string_view::npos; pos = nl + 1)
      out.emplace_back(command_of_numbered(o.substr(pos, nl - pos)));
    sender.written(o.size(), now);
    all.insert(all.end(), out.begin(), out.end());
    return out;
  }
  void reply(const Lines& answers) {
    now += 0.01;
    for (const std::string& a : answers) sender.on_line(a, now);
  }
  bool said(std::string_view part) const {
    for (const std::string& m : messages)
      if (m.find(part) != std::string::npos) return true;
    return false;
  }
  Sender sender;
  double now = 0;
  std::uint64_t line = 0;
  Lines all;
  Lines messages;
};

const Lines kFile = {"M104 S200", "G28", "G1 X10 F600", "G1 X20", "G1 X30", "G1 X40", "G1 X50", "G1 X60"};

}  // namespace

TEST_CASE("homing watch: which commands home and which answers say the printer is not homed",
          "[serial][homing]") {
  CHECK(is_homing_command(Line::parse("G28")));
  CHECK(is_homing_command(Line::parse("g28 X Y")));
  CHECK(is_homing_command(Line::parse("  G28 Z")));
  CHECK(is_homing_command(Line::parse("G028")));
  CHECK_FALSE(is_homing_command(Line::parse("G280")));
  CHECK_FALSE(is_homing_command(Line::parse("G2 X1")));
  CHECK_FALSE(is_homing_command(Line::parse("G28.1")));
  CHECK_FALSE(is_homing_command(Line::parse("M28")));
  CHECK_FALSE(is_homing_command(Line::parse("")));
  CHECK(says_not_homed("Must home axis first: 10.000 10.000 0.300 [0.000]"));  // Klipper
  CHECK(says_not_homed("Home XYZ First"));                                      // Marlin
  CHECK(says_not_homed("Home X First"));
  CHECK(says_not_homed("G0/G1: insufficient axes homed"));  // RepRapFirmware
  CHECK_FALSE(says_not_homed("Move out of range: 10.000 250.000 0.300 [0.000]"));
  CHECK_FALSE(says_not_homed("Unknown command: \"M201\""));
  // Klipper's homing errors (homing.py), whichever command homed.
  CHECK(says_homing_failed("No trigger on x after full movement"));
  CHECK(says_homing_failed("Endstop y still triggered after retract"));
  CHECK(says_homing_failed("Probe triggered prior to movement"));
  CHECK_FALSE(says_homing_failed("Must home axis first: 0.000 0.000 0.000 [0.000]"));
}

TEST_CASE("homing watch: an error answering G28 fails it, a refusal counts only once G28 was taken",
          "[serial][homing]") {
  HomingWatch w;
  // Before any G28 a refused move is the file's own affair.
  CHECK(w.error("Must home axis first: 5.000 0.000 0.000 [0.000]", "G1 X5 F3000", false).empty());
  CHECK(w.message("Home XYZ First").empty());
  // Any error that answers G28 is its homing failing.
  std::string why = w.error("No trigger on x after full movement", "G28", true);
  CHECK(why.find("homing failed") != std::string::npos);
  CHECK(why.find("No trigger on x after full movement") != std::string::npos);
  // A start macro that homes (Klipper's PRINT_START): its error says so.
  CHECK(w.error("No trigger on y after full movement", "PRINT_START BED=60", false).find(
            "homing failed: the printer answered PRINT_START BED=60") != std::string::npos);
  w.acknowledged(false);  // G1 X5
  CHECK_FALSE(w.homed());
  w.acknowledged(true);  // G28 X Y
  CHECK(w.homed());
  CHECK(w.error("Move out of range: 10.000 250.000 0.300 [0.000]", "G1 Y250", false).empty());
  CHECK(w.error("Must home axis first: 5.000 0.000 0.000 [0.000]", "G1 X5", false).find("lost its homing") !=
        std::string::npos);
  CHECK(w.message("Home XYZ First").find("lost its homing") != std::string::npos);
  w.forget();  // a printer reset
  CHECK(w.error("Must home axis first: 5.000 0.000 0.000 [0.000]", "G1 X5", false).empty());
}

TEST_CASE("sender: a failed G28 stops the print: nothing after it goes out and the print fails",
          "[serial][homing]") {
  Run r;
  r.input(kFile);
  CHECK(r.sent() == Lines{"M104 S200", "G28", "G1 X10 F600", "G1 X20"});  // BUFSIZE 4
  r.reply({"ok"});
  CHECK(r.sent() == Lines{"G1 X30"});
  // Klipper: the error, then G28's ok; every move after it is refused.
  r.reply({"!! No trigger on x after full movement"});
  CHECK(r.sender.lost().find("homing failed: the printer answered G28") != std::string::npos);
  r.reply({"ok"});
  CHECK(r.sent().empty());
  for (int i = 0; i < 3; ++i) r.reply({"!! Must home axis first: 0.000 0.000 0.000 [0.000]", "ok"});
  CHECK(r.sent().empty());
  r.reply({"ok"});
  CHECK(r.sender.state() == SenderState::Failed);
  CHECK(r.sender.failure() == r.sender.lost());
  CHECK(std::find(r.all.begin(), r.all.end(), "G1 X40") == r.all.end());
  CHECK(r.said("; the print stops"));
}

TEST_CASE("sender: homing lost mid-print stops it, a move refused before the first G28 does not",
          "[serial][homing]") {
  Run r;
  std::string why;
  // The handler's safe end goes out, and the print still fails.
  r.sender.set_lost_handler([&](std::string_view w) {
    why = std::string(w);
    r.sender.discard_unsent();
    r.sender.reopen_input();
    r.sender.submit("M104 S0", 0, 1);
    r.sender.end_of_input();
  });
  Lines file = {"G1 X1 F600"};
  file.insert(file.end(), kFile.begin(), kFile.end());
  r.input(file);
  CHECK(r.sent() == Lines{"G1 X1 F600", "M104 S200", "G28", "G1 X10 F600"});
  r.reply({"!! Must home axis first: 1.000 0.000 0.000 [0.000]", "ok"});  // before G28: a warning
  CHECK(r.sender.lost().empty());
  r.reply({"ok", "ok", "ok"});  // G28 homed
  CHECK(r.sent() == Lines{"G1 X20", "G1 X30", "G1 X40", "G1 X50"});
  // Its motors went off (an idle timeout): every move from here is refused.
  r.reply({"!! Must home axis first: 10.000 0.000 0.000 [0.000]"});
  CHECK(why.find("lost its homing") != std::string::npos);
  for (int i = 0; i < 20 && r.sender.state() == SenderState::Printing; ++i) {
    r.sent();
    r.reply({"ok"});
  }
  CHECK(r.sender.state() == SenderState::Failed);
  CHECK(r.sender.failure() == why);
  CHECK(std::find(r.all.begin(), r.all.end(), "M104 S0") != r.all.end());
  CHECK(std::find(r.all.begin(), r.all.end(), "G1 X60") == r.all.end());
}
