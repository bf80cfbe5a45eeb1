// gc-send's print control (serial/print_control.hpp) between a pipeline and a
// Sender, against scripted reply streams: the test plays the printer and
// says when each "ok" comes, so what is on its way, what is only handed over
// and what is held back at each request is exact. Each case names what the
// control must do there: pause at the layer's end, pause now, resume to the
// exact position, E and modes, cancel, speed, typed commands put back, and
// the take-back of commands not sent yet.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/layer_marker.hpp"
#include "gcode/core/line.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/serial/control/control_verbs.hpp"
#include "gcode/serial/control/print_control.hpp"
#include "gcode/serial/sender/sender.hpp"
#include "capture.hpp"

using namespace gcode;
using namespace gcode::serial;

namespace {

PrintControlConfig control_config() {
  PrintControlConfig c;
  c.park.given = true;
  c.park.x = 10;
  c.park.y = 200;
  return c;
}

SenderConfig sender_config(std::size_t read_ahead) {
  SenderConfig c;
  c.handshake = false;
  c.read_ahead = read_ahead;
  c.finish_with_m400 = true;
  return c;
}

// The printer's side: the commands that crossed the link, in order, and
// those not answered yet. The pipeline's last stage hands every line to the
// control, as gc-send's session does.
class Rig : private Stage {
 public:
  explicit Rig(std::string text, std::size_t read_ahead = 1, PrintControlConfig config = control_config())
      : text_(std::move(text)),
        pipeline_(markers_, PipelineOptions{.layers = true}),
        sender_(sender_config(read_ahead),
                [](LogLevel, std::uint64_t, std::string_view m) {
                  if (std::getenv("GC_TRACE") != nullptr) std::fprintf(stderr, "%.*s\n", static_cast<int>(m.size()), m.data());
                }),
        control_(config, sender_, diag_, pipeline_.precision()) {
    control_.add_stages(pipeline_);
    pipeline_.add(*this);
    sender_.set_trace(std::getenv("GC_TRACE") != nullptr);
    sender_.start(now_);
    step();
  }

  // Input while the control and the sender take it, then the sender's
  // bytes onto the wire.
  void step() {
    while (!input_done_ && control_.accepts_input() && sender_.wants_input()) {
      if (pos_ == text_.size()) {
        pipeline_.finish();
        input_done_ = true;
        control_.end_of_input(now_);
        break;
      }
      std::size_t nl = text_.find('\n', pos_);
      std::size_t end = nl == std::string::npos ? text_.size() : nl + 1;
      pipeline_.feed(std::string_view(text_).substr(pos_, end - pos_));
      pos_ = end;
      sender_.pump(now_);
    }
    if (input_done_ && control_.input_may_end()) sender_.end_of_input();
    sender_.pump(now_);
    read_wire();
    control_.update(now_);
  }
  // The printer answers the `n` oldest commands in flight.
  void ok(int n = 1) {
    for (int i = 0; i < n && !unanswered_.empty(); ++i) {
      unanswered_.erase(unanswered_.begin());
      now_ += 0.001;
      sender_.on_line("ok", now_);
      step();
    }
  }
  // Answers everything until the sender is done or nothing more comes.
  void run() {
    for (int guard = 0; guard < 100000 && !unanswered_.empty(); ++guard) ok();
  }
  // Answers until input line `source` has crossed the link.
  void run_until_sent(const std::string& command) {
    for (int guard = 0; guard < 100000 && !sent(command) && !unanswered_.empty(); ++guard) ok();
    REQUIRE(sent(command));
  }
  void command(std::string_view verb, std::string argument = {}, double number = 0) {
    ControlCommand c;
    c.verb = find_control_verb(verb);
    REQUIRE(c.verb != nullptr);
    c.argument = std::move(argument);
    c.number = number;
    control_.command(c, now_);
    step();
  }
  bool sent(const std::string& command) const {
    return std::find(wire_.begin(), wire_.end(), command) != wire_.end();
  }
  const std::vector<std::string>& wire() const { return wire_; }
  std::size_t in_flight() const { return unanswered_.size(); }
  PrintControl& control() { return control_; }
  // The clock the control and the sender are given: a millisecond an answer.
  double now() const { return now_; }
  void wait(double seconds) { now_ += seconds; }
  Sender& sender() { return sender_; }

 private:
  void line(const TrackedLine& t, Emitter&) override { control_.line(t, now_); }
  void layer(const LayerInfo& info, const MachineState& before, Emitter&) override {
    control_.layer(info, before, now_);
  }
  void end_code(const EndCodeInfo&, const MachineState& before, Emitter&) override {
    control_.end_code(before, now_);
  }
  bool reads_state() const override { return true; }

  // "N12 G1 X1*34\n" -> "G1 X1".
  void read_wire() {
    std::string_view out = sender_.output();
    std::size_t pos = 0;
    for (std::size_t nl; (nl = out.find('\n', pos)) != std::string_view::npos; pos = nl + 1) {
      std::string_view l = out.substr(pos, nl - pos);
      if (l.starts_with('N')) {
        l.remove_prefix(l.find(' ') + 1);
        l = l.substr(0, l.rfind('*'));
      }
      wire_.emplace_back(l);
      unanswered_.emplace_back(l);
    }
    sender_.written(pos, now_);
  }

  Diagnostics diag_{"gc-send", -1};
  std::string text_;
  std::size_t pos_ = 0;
  bool input_done_ = false;
  LayerMarkers markers_;
  Pipeline pipeline_;
  Sender sender_;
  PrintControl control_;
  double now_ = 0;
  std::vector<std::string> wire_;
  std::vector<std::string> unanswered_;
};

// Three Cura layers of a few moves each, absolute E.
const std::string kThreeLayers =
    "G28\nG90\nM82\nM104 S200\nG92 E0\n"
    ";LAYER:0\nG1 Z0.2 F600\nG1 X10 Y10 F3000\nG1 X20 Y10 E1 F1200\nG1 X20 Y20 E2\nG1 X10 Y20 E3\n"
    ";LAYER:1\nG1 Z0.4 F600\nG1 X20 Y20 E4 F1200\nG1 X20 Y30 E5\nG1 X10 Y30 E6\nG1 X10 Y40 E7\n"
    ";LAYER:2\nG1 Z0.6 F600\nG1 X20 Y40 E8 F1200\nG1 X20 Y50 E9\n"
    "M104 S0\n";

// The input's commands as sent.
std::vector<std::string> commands(std::string_view text) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t nl = text.find('\n', pos);
    std::string_view l = text.substr(pos, nl - pos);
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    if (!l.empty() && l[0] != ';') out.emplace_back(l);
  }
  return out;
}

// The wire without the lines gc-send made itself: the file's commands.
std::vector<std::string> file_commands_on(const std::vector<std::string>& wire, std::string_view text) {
  std::vector<std::string> file = commands(text), out;
  std::size_t next = 0;
  for (const std::string& w : wire)
    if (next < file.size() && w == file[next]) {
      out.push_back(w);
      ++next;
    }
  return out;
}

}  // namespace

TEST_CASE("print control: without requests the file goes out as it is", "[serial][print_control]") {
  Rig rig(kThreeLayers);
  rig.run();
  std::vector<std::string> expected = commands(kThreeLayers);
  expected.emplace_back("M400");
  CHECK(rig.wire() == expected);
  CHECK(rig.sender().state() == SenderState::Done);
  CHECK(rig.control().state() == PrintState::Printing);
  CHECK(rig.control().pauses().empty());
}

// The wire from the `from`th command on.
std::vector<std::string> tail_of(const Rig& rig, std::size_t from) {
  return std::vector<std::string>(rig.wire().begin() + static_cast<std::ptrdiff_t>(from), rig.wire().end());
}

using Lines = std::vector<std::string>;

// A pause asked for in layer 2, done at its end; returns how many lines
// went out by then.
std::size_t pause_in_layer_two(Rig& rig) {
  rig.run_until_sent("G1 X20 Y20 E4 F1200");
  rig.command("pause");
  rig.run();
  REQUIRE(rig.control().state() == PrintState::Paused);
  return rig.wire().size();
}

const Lines kStartAndLayer1 = {"G28", "G90", "M82", "M104 S200", "G92 E0", "G1 Z0.2 F600", "G1 X10 Y10 F3000",
                               "G1 X20 Y10 E1 F1200", "G1 X20 Y20 E2", "G1 X10 Y20 E3"};

TEST_CASE("print control: a pause rushes the rest of the layer, parks at its end, holds the next",
          "[serial][print_control]") {
  Rig rig(kThreeLayers);
  rig.run_until_sent("G1 X20 Y20 E4 F1200");  // layer 2 under way; its next move is handed over already
  rig.command("pause");
  CHECK(rig.control().state() == PrintState::Pausing);
  CHECK(rig.control().state_label() == "pausing");
  REQUIRE(rig.control().pauses().size() == 1);
  rig.run();
  Lines expected = kStartAndLayer1;
  // The move already handed over keeps its speed; the rest of the layer
  // runs at 3 times it (--rush); then the block: retract 2 mm, lift 2 mm
  // above the layer, park. Nothing of layer 3.
  for (const char* l : {"G1 Z0.4 F600", "G1 X20 Y20 E4 F1200", "G1 X20 Y30 E5", "G1 X10 Y30 E6 F3600",
                        "G1 X10 Y40 E7", "G1 E5 F2100", "G1 Z2.4 F600", "G1 X10 Y200 F3600"})
    expected.emplace_back(l);
  CHECK(rig.wire() == expected);
  CHECK(rig.sender().idle());
  CHECK(rig.control().state() == PrintState::Paused);
  CHECK(rig.control().state_label() == "paused");
  CHECK_FALSE(rig.control().accepts_input());
  CHECK_FALSE(rig.control().input_may_end());
  const PauseRecord& p = rig.control().pauses().back();
  CHECK(p.request == "pause");
  CHECK(p.layer == 2);
  CHECK(p.paused_before_layer == 3);
  CHECK(p.input_line == 17);  // G1 X10 Y40 E7
  CHECK(p.block);
  CHECK(p.block_number == 16);
  CHECK(p.wall_paused >= 0);  // the printer has done the block
}

TEST_CASE("print control: resume returns to the exact position, E, modes and speed, then the next layer",
          "[serial][print_control]") {
  Rig rig(kThreeLayers);
  const std::size_t parked = pause_in_layer_two(rig);
  rig.command("resume");
  CHECK(rig.control().state() == PrintState::Printing);
  rig.run();
  // Over the layer's last point at the safe height, down to its Z, the
  // retraction pushed back, the E coordinate and mode, the feed rate; then
  // layer 3 as the file has it.
  CHECK(tail_of(rig, parked) == Lines{"G1 X10 Y40 F3600", "G1 Z0.4 F600", "G1 E7 F2100", "M82", "G92 E7", "G1 F3600",
                                      "G1 Z0.6 F600", "G1 X20 Y40 E8 F1200", "G1 X20 Y50 E9", "M104 S0", "M400"});
  CHECK(rig.sender().state() == SenderState::Done);
  CHECK(rig.control().pauses().size() == 1);
  CHECK(rig.control().paused_seconds(1e9) >= 0);
}

// The pause log's times are the clock the control is given, as the
// sender's are: a request, the printer done with the block, the resume.
TEST_CASE("print control: a pause's times are the caller's clock, not the wall's", "[serial][print_control]") {
  Rig rig(kThreeLayers);
  rig.run_until_sent("G1 X20 Y20 E4 F1200");
  rig.wait(100);
  const double asked = rig.now();
  rig.command("pause");
  CHECK(rig.control().pauses().back().wall_request == asked);
  rig.run();
  REQUIRE(rig.control().state() == PrintState::Paused);
  const double reached = rig.control().pauses().back().wall_paused;
  CHECK(reached > asked);
  CHECK(reached < asked + 1);  // a millisecond an answer, a few dozen answers
  rig.wait(30);
  CHECK(rig.control().paused_seconds(rig.now()) == Approx(rig.now() - reached));
  const double resumed = rig.now();
  rig.command("resume");
  rig.run();
  // Resumed: what stood still stays counted, later seconds are not.
  CHECK(rig.control().paused_seconds(rig.now() + 1000) == Approx(resumed - reached));
}

TEST_CASE("print control: commands typed while paused are put back before the resume block",
          "[serial][print_control]") {
  Rig rig(kThreeLayers);
  const std::size_t parked = pause_in_layer_two(rig);
  // Relative moves, relative E, a purge, a colder nozzle.
  for (const char* typed : {"G91", "G1 X5 Y5 F3000", "M83", "G1 E10 F300", "M104 S180"})
    rig.command("gcode", typed);
  CHECK(rig.control().user_commands() == 5);
  rig.run();
  rig.command("resume");
  rig.run();
  // Absolute again (on Marlin G90 makes E absolute too: no M82), up over
  // everything held (layer 3's Z 0.6 + 2), back to the park, the E the block
  // left (E5), the nozzle heated back; then the resume block as without
  // typed commands.
  CHECK(tail_of(rig, parked) ==
        Lines{"G91", "G1 X5 Y5 F3000", "M83", "G1 E10 F300", "M104 S180",                        // typed
              "G90", "G1 Z2.6 F600", "G1 X10 Y200 F3600", "G1 Z2.4 F600", "G92 E5", "M109 S200", "G1 F3600",  // put back
              "G1 X10 Y40 F3600", "G1 Z0.4 F600", "G1 E7 F2100", "M82", "G92 E7", "G1 F3600",     // resume block
              "G1 Z0.6 F600", "G1 X20 Y40 E8 F1200", "G1 X20 Y50 E9", "M104 S0", "M400"});
}

TEST_CASE("print control: typed commands only while paused, and only for the printer", "[serial][print_control]") {
  Rig rig(kThreeLayers);
  rig.ok(2);
  const std::size_t before = rig.wire().size();
  rig.command("gcode", "G1 X50");  // printing: refused
  rig.command("pause");
  rig.run();
  rig.command("gcode", "@pause");   // a host command
  rig.command("gcode", "M110 N5");  // the numbering is gc-send's
  rig.command("gcode", "; a note");
  CHECK(rig.control().user_commands() == 0);
  for (std::size_t i = before; i < rig.wire().size(); ++i) {
    INFO(rig.wire()[i]);
    CHECK(rig.wire()[i].find("X50") == std::string::npos);
    CHECK(rig.wire()[i].find("M110") == std::string::npos);
  }
}

TEST_CASE("print control: pause now takes back what is not sent yet and parks after what is",
          "[serial][print_control]") {
  Rig rig(kThreeLayers, 8);  // a read-ahead of 8 commands
  rig.ok(3);
  REQUIRE(rig.in_flight() == 4);
  REQUIRE(rig.sender().pending() == 8);
  rig.command("pause now");
  // The 8 unsent commands wait after the block (3 lines), which parks from
  // the last command sent (G1 X10 Y10, E0).
  CHECK(rig.sender().pending() == 3);
  rig.run();
  CHECK(rig.wire() == Lines{"G28", "G90", "M82", "M104 S200", "G92 E0", "G1 Z0.2 F600", "G1 X10 Y10 F3000",
                            "G1 E-2 F2100", "G1 Z2.2 F600", "G1 X10 Y200 F3600"});
  const PauseRecord& p = rig.control().pauses().back();
  CHECK(p.request == "pause now");
  CHECK(p.input_line == 8);
  CHECK(p.paused_before_layer == 0);
  rig.command("resume");
  rig.run();
  // Back to where the last sent command left the head, then every command
  // taken back, once, in order.
  Lines expected = {"G28", "G90", "M82", "M104 S200", "G92 E0", "G1 Z0.2 F600", "G1 X10 Y10 F3000",
                    "G1 E-2 F2100", "G1 Z2.2 F600", "G1 X10 Y200 F3600",
                    "G1 X10 Y10 F3600", "G1 Z0.2 F600", "G1 E0 F2100", "M82", "G92 E0", "G1 F3000"};
  for (std::size_t i = 7; i < commands(kThreeLayers).size(); ++i) expected.push_back(commands(kThreeLayers)[i]);
  expected.emplace_back("M400");
  CHECK(rig.wire() == expected);
  CHECK(rig.sender().state() == SenderState::Done);
}

TEST_CASE("print control: pause now while pausing stops at once", "[serial][print_control]") {
  Rig rig(kThreeLayers, 8);
  rig.ok(3);
  rig.command("pause");  // in the start code: before layer 1
  CHECK(rig.control().state() == PrintState::Pausing);
  rig.command("pause now");
  CHECK(rig.control().state() == PrintState::Paused);
  REQUIRE(rig.control().pauses().size() == 1);
  CHECK(rig.control().pauses().back().request == "pause");
  rig.run();
  CHECK(tail_of(rig, 7) == Lines{"G1 E-2 F2100", "G1 Z2.2 F600", "G1 X10 Y200 F3600"});
}

TEST_CASE("print control: a resume before the layer's end calls the pause off", "[serial][print_control]") {
  Rig rig(kThreeLayers);
  rig.run_until_sent("G1 X20 Y20 E4 F1200");
  rig.command("pause");
  rig.command("resume");
  CHECK(rig.control().state() == PrintState::Printing);
  CHECK(rig.control().pauses().empty());
  rig.run();
  std::vector<std::string> expected = commands(kThreeLayers);
  expected.emplace_back("M400");
  // Only F words differ: what ran while the rush was on.
  CHECK(file_commands_on(rig.wire(), kThreeLayers).size() < expected.size());
  CHECK(rig.wire().size() == expected.size());
  CHECK(rig.wire().back() == "M400");
  CHECK(std::none_of(rig.wire().begin(), rig.wire().end(), [](const std::string& l) { return l.find("Y200") != std::string::npos; }));
}

TEST_CASE("print control: cancel leaves out what is not sent yet and parks from what is",
          "[serial][print_control]") {
  Rig rig(kThreeLayers, 8);
  rig.ok(3);
  REQUIRE(rig.sender().pending() == 8);
  rig.command("cancel");
  CHECK(rig.control().cancelled());
  CHECK_FALSE(rig.control().accepts_input());
  rig.run();
  CHECK(rig.wire() == Lines{"G28", "G90", "M82", "M104 S200", "G92 E0", "G1 Z0.2 F600", "G1 X10 Y10 F3000",
                            "G1 E-2 F2100", "G1 Z2.2 F600", "G1 X10 Y200 F3600",  // the safe end: retract, lift, park
                            "M104 S0", "M140 S0", "M107", "M84", "M400"});        // heaters and motors off
  CHECK(rig.sender().state() == SenderState::Done);
}

TEST_CASE("print control: a cancel after the whole file was handed over still parks and turns the heaters off",
          "[serial][print_control]") {
  Rig rig(kThreeLayers, 64);  // every command handed over: the sender was told the input ended
  rig.ok(3);
  REQUIRE(rig.sender().pending() == commands(kThreeLayers).size() - 7);
  rig.command("cancel");
  rig.run();
  CHECK(rig.wire() == Lines{"G28", "G90", "M82", "M104 S200", "G92 E0", "G1 Z0.2 F600", "G1 X10 Y10 F3000",
                            "G1 E-2 F2100", "G1 Z2.2 F600", "G1 X10 Y200 F3600",
                            "M104 S0", "M140 S0", "M107", "M84", "M400"});
  CHECK(rig.sender().state() == SenderState::Done);
}

TEST_CASE("print control: a pause in the end code after the whole file was handed over parks and resumes",
          "[serial][print_control]") {
  const std::string text = kThreeLayers + "G1 X0 Y0 F3000\nM84\n";
  Rig rig(text, 64);
  rig.run_until_sent("M104 S0");  // the end code under way
  rig.command("pause now");
  rig.run();
  CHECK(rig.control().state() == PrintState::Paused);
  CHECK(rig.wire().back().find("Y200") != std::string::npos);  // parked
  rig.command("resume");
  rig.run();
  CHECK(rig.sender().state() == SenderState::Done);
  CHECK(rig.wire().back() == "M400");
  CHECK(file_commands_on(rig.wire(), text) == commands(text));
}

TEST_CASE("print control: a cancel while paused does not park again", "[serial][print_control]") {
  Rig rig(kThreeLayers);
  const std::size_t parked = pause_in_layer_two(rig);
  rig.command("cancel");
  rig.run();
  CHECK(tail_of(rig, parked) == Lines{"M104 S0", "M140 S0", "M107", "M84", "M400"});
}

TEST_CASE("print control: Ctrl-C cancels once", "[serial][print_control]") {
  Rig rig(kThreeLayers, 8);
  rig.ok(3);
  CHECK(rig.control().interrupt());
  CHECK(rig.control().cancelled());
  CHECK_FALSE(rig.control().interrupt());
}

TEST_CASE("print control: speed changes the moves that follow, from their effective feed rate",
          "[serial][print_control]") {
  Rig rig(kThreeLayers);
  rig.ok(6);  // G1 X10 Y10 sent; the next handed over
  rig.command("speed", "", 2);
  CHECK(rig.control().speed() == 2);
  rig.run();
  // The move handed over already keeps its speed; from the next on, twice
  // the file's: an F where the move inherits one (E5 runs at 2 x 1200), the
  // file's F words doubled, travel too (Z moves keep theirs).
  CHECK(tail_of(rig, 10) == Lines{"G1 Z0.4 F600", "G1 X20 Y20 E4 F1200", "G1 X20 Y30 E5 F2400", "G1 X10 Y30 E6",
                                  "G1 X10 Y40 E7", "G1 Z0.6 F600", "G1 X20 Y40 E8 F2400", "G1 X20 Y50 E9",
                                  "M104 S0", "M400"});
}

TEST_CASE("print control: the file's own pause holds the lines after it", "[serial][print_control]") {
  const std::string text = "G28\nG90\nG1 Z0.2 F600\n;@pause\nG1 X10 Y10 F3000\nM84\n";
  Rig rig(text);
  rig.run();
  CHECK(rig.wire() == Lines{"G28", "G90", "G1 Z0.2 F600"});
  CHECK(rig.control().state() == PrintState::Paused);
  REQUIRE(rig.control().pauses().size() == 1);
  CHECK_FALSE(rig.control().pauses().back().block);
  CHECK(rig.control().host_commands() == 0);
  rig.command("resume");
  rig.run();
  // No block to undo: the file goes on where it stopped.
  CHECK(rig.wire() == Lines{"G28", "G90", "G1 Z0.2 F600", "G1 X10 Y10 F3000", "M84", "M400"});
}

TEST_CASE("print control: the printer's host actions", "[serial][print_control]") {
  Rig rig(kThreeLayers);
  rig.run_until_sent("G1 X20 Y20 E4 F1200");
  rig.control().action("paused", rig.now());  // a report, not a request
  CHECK(rig.control().state() == PrintState::Printing);
  rig.control().action("pause", rig.now());
  CHECK(rig.control().state() == PrintState::Pausing);
  CHECK(rig.control().pauses().back().request == "//action:pause");
  rig.run();
  CHECK(rig.control().state() == PrintState::Paused);
  rig.control().action("resume", rig.now());
  CHECK(rig.control().state() == PrintState::Printing);
  rig.step();
  rig.control().action("cancel", rig.now());
  CHECK(rig.control().cancelled());
}

// A file that does not say how big the bed is, and no --park: nowhere to
// park, yet the nozzle must not stay on the part.
PrintControlConfig unparked_config(double max_z = 0) {
  PrintControlConfig c;
  c.pause.max_z = max_z;
  c.pause.purge = 5;  // would drop on the part: left out
  return c;
}

TEST_CASE("print control: without a park position a pause retracts and lifts where it is and returns exactly",
          "[serial][print_control]") {
  Rig rig(kThreeLayers, 1, unparked_config());
  const std::size_t paused = pause_in_layer_two(rig);
  // Retract 2 mm, lift 2 mm above the layer; no travel, no purge.
  CHECK(tail_of(rig, paused - 2) == Lines{"G1 E5 F2100", "G1 Z2.4 F600"});
  rig.command("resume");
  rig.run();
  // Straight down to the layer's Z, the retraction pushed back, E, mode
  // and feed rate as the file had them; then layer 3.
  CHECK(tail_of(rig, paused) == Lines{"G1 Z0.4 F600", "G1 E7 F2100", "M82", "G92 E7", "G1 F3600", "G1 Z0.6 F600",
                                      "G1 X20 Y40 E8 F1200", "G1 X20 Y50 E9", "M104 S0", "M400"});
  CHECK(rig.sender().state() == SenderState::Done);
}

TEST_CASE("print control: without a park position the lift stops at the printer's height", "[serial][print_control]") {
  Rig rig(kThreeLayers, 1, unparked_config(1.5));
  const std::size_t paused = pause_in_layer_two(rig);
  CHECK(tail_of(rig, paused - 2) == Lines{"G1 E5 F2100", "G1 Z1.5 F600"});
  rig.command("resume");
  rig.run();
  CHECK(tail_of(rig, paused).front() == "G1 Z0.4 F600");
}

TEST_CASE("print control: without a park position a cancel retracts and lifts, then heaters and motors off",
          "[serial][print_control]") {
  Rig rig(kThreeLayers, 8, unparked_config());
  rig.ok(3);
  rig.command("cancel");
  rig.run();
  CHECK(rig.wire() == Lines{"G28", "G90", "M82", "M104 S200", "G92 E0", "G1 Z0.2 F600", "G1 X10 Y10 F3000",
                            "G1 E-2 F2100", "G1 Z2.2 F600", "M104 S0", "M140 S0", "M107", "M84", "M400"});
}

TEST_CASE("print control: what the journal keeps of each verb, a resumed control holds again",
          "[serial][print_control]") {
  Rig before(kThreeLayers);
  before.ok(6);
  before.command("speed", "", 2.5);
  for (const ControlVerb& v : control_verbs()) {
    if (v.journal_field.empty()) continue;
    INFO(v.name);
    Rig after(kThreeLayers);
    v.restore(after.control(), v.journal(before.control()));
    CHECK(v.journal(after.control()) == v.journal(before.control()));
    // A journal without the field leaves the control as it starts.
    Rig fresh(kThreeLayers);
    std::string start = v.journal(fresh.control());
    v.restore(fresh.control(), "");
    CHECK(v.journal(fresh.control()) == start);
  }
  CHECK(find_control_verb("speed")->journal(before.control()) == "2.5");
}
