// gc-send's pause, resume and cancel from the control FIFO, on the in-process
// virtual printer and its executed-command log, with real fixtures cut into
// 0.2 mm pieces by gc-subdivide:
//  * `pause` at several moments: the pause block comes right after the last
//    command of the layer the request came in, before any command of the
//    next; the moves between the request and the layer's end ran at rush
//    speed (capped); after `resume` the position, E, modes and F are those
//    before the block; the rest is executed exactly (nothing lost, nothing
//    twice);
//  * `pause now`: the nozzle's path from the request to the end of motion,
//    measured from the log on the simulated clock (16-block planner, 4-slot
//    queue, 250000 baud), at most the planner's 16 moves and the pacer's 2,
//    and what gc-send reports agrees, on a printer at the file's speed and
//    on one twice as fast that gc-send is not told of;
//  * @pause, ;@pause and --pause-on M0 hold the host and are not sent;
//  * the FIFO is refused when it is a regular file or writable by others;
//  * cancel ends safely with exit status 0.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/transform/pause_sequence.hpp"
#include "control_run.hpp"
#include "serial_check.hpp"
#include "test_support.hpp"

using gctest::Checked;
using gctest::Executed;
using gctest::PauseRun;
using gctest::check_one_pause;
using gctest::number_after;
using gctest::quote;
using gctest::send_with_control;
using gctest::state_after;
using gctest::tool_path;
using gctest::without_f;

namespace {

// The start code and first three layers of a fixture in 0.2 mm pieces,
// written once per run.
const std::string& pause_pieces() {
  static std::string path;
  if (path.empty()) {
    path = gctest::temp_dir() + "/pieces.gcode";
    auto r = gctest::run(quote(tool_path("gc-subdivide")) + " --max 0.2 " +
                         quote(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")) +
                         " | awk '/^;LAYER_CHANGE/ { if (++n == 4) exit } { print }' > " + quote(path));
    REQUIRE(r.status == 0);
  }
  return path;
}

// The layer of every input line, as the library's pipeline sees it (the
// end code: -1).
std::map<std::uint64_t, int> layers_of(const std::string& text) {
  struct Collect : gcode::Stage {
    std::map<std::uint64_t, int> layer;
    void line(const gcode::TrackedLine& t, gcode::Emitter& out) override {
      layer[t.raw.number] = t.region == gcode::Region::EndCode ? -1 : t.layer;
      out.pass(t);
    }
  } collect;
  gcode::LayerMarkers markers;
  gcode::Pipeline p(markers);
  p.add(collect);
  p.run_text(text);
  return collect.layer;
}

// A cancel's park in the executed log: the input's commands up to the
// cancel, then moves that never push filament nor go down and retract
// exactly the pause's 2 mm, or nothing where the file had retracted itself
// (the pause block never retracts twice). Returns whether it had.
bool check_cancel_park(const std::vector<Executed>& log, const std::vector<gctest::SentCommand>& input) {
  std::size_t prefix = 0;
  while (prefix < input.size() && prefix < log.size() && log[prefix].command == input[prefix].text) ++prefix;
  REQUIRE(prefix > 0);
  gcode::MachineState s;
  gcode::RetractionTracker file_retraction;
  for (std::size_t i = 0; i < prefix; ++i) file_retraction.observe(s.apply(gcode::Line::parse(log[i].command)));
  const bool retracted = file_retraction.pending() > 1e-9;
  double z = s.at(gcode::kZ).to_double(), pushed = 0;
  for (std::size_t i = prefix; i < log.size(); ++i) {
    INFO("park line " << log[i].command);
    gcode::Move m = s.apply(gcode::Line::parse(log[i].command));
    pushed += m.filament;
    CHECK(m.filament <= 0);
    CHECK(s.at(gcode::kZ).to_double() >= z - 1e-9);
  }
  // Counted from a command never sent, it would be that command's E short.
  CHECK(pushed == Approx(retracted ? 0.0 : -2.0).margin(1e-9));
  return retracted;
}

}  // namespace

TEST_CASE("gc-send pause: at the end of the request's layer, rushed, resumed exactly, nothing lost", "[gc-send][pause]") {
  const std::string& file = pause_pieces();
  std::string text = gctest::read_file(file);
  auto input = gctest::commands_of(text);
  auto layer = layers_of(text);
  // Instant moves: the run lasts as long as the link takes; the request
  // goes as layer 1 begins, after 4000 commands (in layer 1) and after 10000
  // (layer 2), and lands a little later each time.
  for (const char* when : {"at_layer 1", "executed 4000", "executed 10000"}) {
    INFO("pause once " << when);
        // (--no-pace: with moves that take no time, pacing by their real
    // durations only slows the run down.)
    PauseRun r = send_with_control(file, "time-scale=20,instant-moves,heat-rate=1000", "--no-pace --rush 3 --max-speed 200",
                                   std::string(when) + "; echo pause > \"$F\"; paused; echo resume > \"$F\"");
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    std::uint64_t last = static_cast<std::uint64_t>(number_after(r.result.err, "pause block sent after input line "));
    double asked_layer = number_after(r.result.err, "pause: finishing layer ");
    REQUIRE(asked_layer >= 1);
    Checked c = check_one_pause(r.log, input, last);
    // Right at the layer's end: the last command before the block is of the
    // request's layer, the first after it of the next (the file ends after
    // layer 3: a pause asked there comes before what the file has after its
    // last extrusion, or at its end).
    CHECK(layer[input[c.prefix - 1].source_line] == static_cast<int>(asked_layer));
    if (c.prefix < input.size() && layer[input[c.prefix].source_line] == -1) {
      CHECK(asked_layer == 3);
    } else if (c.prefix < input.size()) {
      CHECK(layer[input[c.prefix].source_line] == static_cast<int>(asked_layer) + 1);
    } else {
      CHECK(asked_layer == 3);
    }
    // The block has no move into the next layer: its heights are the
    // layer's own or above it (lift), and it ends where it began.
    gcode::MachineState before = state_after(r.log, c.prefix);
    gcode::MachineState after = state_after(r.log, c.prefix + c.block);
    for (std::size_t i = c.prefix; i < c.prefix + c.block; ++i) {
      gcode::MachineState s = state_after(r.log, i + 1);
      CHECK(s.at(gcode::kZ) >= before.at(gcode::kZ));
    }
    for (int a : {gcode::kX, gcode::kY, gcode::kZ, gcode::kE}) CHECK(after.at(a) == before.at(a));
    CHECK(after.relative_xyz == before.relative_xyz);
    CHECK(after.relative_e == before.relative_e);
    CHECK(after.feedrate == before.feedrate);
    // The rush: from the request on, every extruding move of the layer ran
    // at three times its speed, at most 200 mm/s; the first few after the
    // request were already handed to the sender.
    std::uint64_t from = static_cast<std::uint64_t>(number_after(r.result.err, "times the speed (after input line "));
    gcode::MachineState sent, original;
    std::size_t rushed = 0, slow = 0;
    for (std::size_t i = 0; i < c.prefix; ++i) {
      gcode::Move got = sent.apply(gcode::Line::parse(r.log[i].command));
      gcode::Move was = original.apply(gcode::Line::parse(input[i].text));
      if (!was.extruding || was.xy_length <= 0) continue;
      double want = std::min(3 * was.feedrate, 200.0 * 60);
      if (input[i].source_line <= from) {
        CHECK(got.feedrate == was.feedrate);
      } else if (std::fabs(got.feedrate - want) < 1) {
        ++rushed;
      } else {
        CHECK(got.feedrate == was.feedrate);
        CHECK(rushed == 0);  // only before the rush took hold
        ++slow;
      }
    }
    CHECK(slow <= 8);
    CHECK(rushed > 0);
  }
}

namespace {

// `speed`: the printer runs its moves that many times faster than the
// file says, and gc-send is not told (its pacer learns it from the answers).
void check_pause_now(double speed) {
  const std::string& file = pause_pieces();
  auto input = gctest::commands_of(gctest::read_file(file));
  // On the simulated clock (virtual:simulated-clock) gc-send reads every
  // answer in time however busy the machine is: the figures below are its
  // model's and the printer's, never the host's. The request goes once the
  // printer has run so many commands (inside layer 1's walls and infill; it
  // lands a few commands later each run, as the machine lets the script see).
  for (const char* count : {"1500", "2500", "4000", "6000"}) {
    INFO("pause now after " << count << " commands, printer at " << speed << " x");
    PauseRun r = send_with_control(file, "simulated-clock,time-scale=5,heat-rate=1000,speed-factor=" + std::to_string(speed), "",
                                   std::string("executed ") + count +
                                       "; echo pause now > \"$F\"; paused; echo cancel > \"$F\"");
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    double asked = number_after(r.result.err, "pause now: asked at printer time ");
    // (The log holds the input's commands and the blocks; gc-send's own
    // pace probes and questions are left out of it.)
    std::size_t prefix = 0;
    {
      std::uint64_t last = static_cast<std::uint64_t>(number_after(r.result.err, "pause block sent after input line "));
      while (prefix < input.size() && input[prefix].source_line <= last) ++prefix;
      for (std::size_t i = 0; i < prefix; ++i) REQUIRE(r.log[i].command == input[i].text);
    }
    // The printer's motion, block by block, as the model runs it: a move
    // starts when it has left the queue and the one before has ended.
    gcode::MachineState s;
    double end = 0, path = 0;
    int moves_after = 0;  // moves that ran, whole or in part, after the request
    for (std::size_t i = 0; i < prefix; ++i) {
      const Executed& e = r.log[i];
      gcode::Move m = s.apply(gcode::Line::parse(e.command));
      double length = m.length > 0 ? m.length : std::fabs(m.filament);
      if (length <= 0 || (m.kind != gcode::MoveKind::Linear && m.kind != gcode::MoveKind::Arc)) continue;
      double start = std::max(e.time, end);
      end = start + length / ((m.feedrate > 0 ? m.feedrate : 1500) / 60) / speed;
      if (end <= asked) continue;
      ++moves_after;
      if (m.length > 0) path += m.length * std::min(1.0, (end - asked) / (end - start));
    }
    INFO("path after the request " << path << " mm in " << moves_after << " moves, " << end - asked << " s");
    // At most the planner's 16 blocks, and the 2 a pacer's bet on a probe's
    // word may hold beyond them (Pacer::kCreditInFlight): 3.6 mm of 0.2 mm
    // pieces.
    CHECK(moves_after <= 16 + 2);
    CHECK(path <= 3.6);
    // The planner was busy: a real measurement.
    CHECK(moves_after > 1);
    // gc-send's figure is its model of the planner at the request, kept
    // from the answers as they arrive: exact on the simulated clock.
    double reported = number_after(r.result.err, "motion went on ");
    CHECK(std::fabs(reported - path) < 0.05);
  }
}

}  // namespace

TEST_CASE("gc-send pause now: the nozzle stops within the planner's blocks and gc-send's figure, 0.2 mm pieces",
          "[gc-send][pause]") {
  check_pause_now(1);
}

TEST_CASE("gc-send pause now: within the planner's blocks on a printer twice as fast as gc-send's model",
          "[gc-send][pause]") {
  // A pacer that learnt a factor above the printer's would hold more moves
  // in flight than its planner takes.
  check_pause_now(2);
}

TEST_CASE("gc-send: @pause, a comment @pause and --pause-on M0 hold the host and are not sent", "[gc-send][pause]") {
  std::string dir = gctest::temp_dir();
  std::string base = gctest::head_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 3000);
  for (const char* marker : {"@pause", ";@pause", "M0 Change the colour"}) {
    INFO(marker);
    // In the middle of the first layer.
    std::size_t at = 0;
    for (int i = 0; i < 2500; ++i) at = base.find('\n', at) + 1;
    std::string text = base.substr(0, at) + marker + "\n" + base.substr(at);
    std::string file = dir + "/with_pause.gcode";
    gctest::write_file(file, text);
    std::string args = std::string(marker).rfind("M0", 0) == 0 ? "--pause-on M0,M1,M25,M601" : "";
    PauseRun r = send_with_control(file, "time-scale=100,instant-moves,heat-rate=1000", args,
                                   "paused; sleep 0.2; echo resume > \"$F\"");
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    CHECK(r.result.err.find("the file's pause at line 2501") != std::string::npos);
    auto input = gctest::commands_of(text);
    // commands_of leaves out host commands but not M0: take it out here.
    std::vector<gctest::SentCommand> expected;
    for (auto& c : input)
      if (c.text.rfind("M0", 0) != 0) expected.push_back(c);
    REQUIRE(r.log.size() == expected.size() + 1);
    for (std::size_t i = 0; i < expected.size(); ++i) REQUIRE(r.log[i].command == expected[i].text);
    // The printer stood still while the host held the lines.
    double gap = 0;
    for (std::size_t i = 1; i < r.log.size(); ++i) gap = std::max(gap, r.log[i].time - r.log[i - 1].time);
    CHECK(gap > 0.15 * 100);
  }
}

TEST_CASE("gc-send: the control FIFO is refused when it is a regular file or writable by others", "[gc-send][pause]") {
  std::string dir = gctest::temp_dir();
  std::string regular = dir + "/regular";
  gctest::write_file(regular, "");
  auto r = gctest::run(quote(tool_path("gc-send")) + " -q --control " + quote(regular) + " " +
                       quote(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")));
  CHECK(r.status == 1);
  CHECK(r.err.find("not a FIFO") != std::string::npos);
  std::string open = dir + "/open.fifo";
  REQUIRE(mkfifo(open.c_str(), 0600) == 0);
  chmod(open.c_str(), 0666);
  r = gctest::run(quote(tool_path("gc-send")) + " -q --control " + quote(open) + " " +
                  quote(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")));
  CHECK(r.status == 1);
  CHECK(r.err.find("can be written by others") != std::string::npos);
}

TEST_CASE("gc-send: cancel parks, turns heaters off and exits 0, and junk in the FIFO changes nothing", "[gc-send][pause]") {
  const std::string& file = pause_pieces();
  PauseRun r = send_with_control(file, "time-scale=5,instant-moves,heat-rate=1000", "",
                                 "head -c 200000 /dev/urandom > \"$F\"; echo > \"$F\"; echo status > \"$F\"; echo bogus > \"$F\"; "
                                 "executed 2000; "
                                 "echo cancel > \"$F\"");
  INFO(r.result.err);
  CHECK(r.result.status == 0);
  CHECK(r.result.err.find("cancelled after input line") != std::string::npos);
  CHECK(r.result.err.find("unknown command 'bogus'") != std::string::npos);
  REQUIRE(r.log.size() > 6);
  std::vector<std::string> tail;
  for (std::size_t i = r.log.size() - 5; i < r.log.size(); ++i) tail.push_back(r.log[i].command);
  CHECK(tail == std::vector<std::string>{"M104 S0", "M140 S0", "M107", "M84", "M400"});
  // The park starts where the printer is.
  check_cancel_park(r.log, gctest::commands_of(gctest::read_file(file)));
}

TEST_CASE("gc-send: a cancel in absolute E parks from the last command on its way", "[gc-send][pause]") {
  // Paced (moves take their time): a command or two wait in the sender.
  // Those are left out, so the park's absolute retraction must be counted
  // from before them, or it would push their filament.
  std::string file = gctest::temp_dir() + "/abs_pieces.gcode";
  REQUIRE(gctest::run(quote(tool_path("gc-subdivide")) + " --max 0.2 " +
                      quote(gctest::fixture_path("cura_cube_0.2_abs_zhop_skirt.gcode")) +
                      " | awk '/^;LAYER:2/ { exit } { print }' > " + quote(file))
              .status == 0);
  auto input = gctest::commands_of(gctest::read_file(file));
  // On the simulated clock the pacer holds moves back as on a quiet host,
  // however busy the machine is; the cancel goes after so many commands.
  std::size_t left_out = 0;
  for (const char* count : {"1500", "3000", "4500"}) {
    INFO("cancel after " << count << " commands");
    PauseRun r = send_with_control(file, "simulated-clock,time-scale=5,heat-rate=1000", "",
                                   std::string("executed ") + count + "; echo cancel > \"$F\"");
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    const bool retracted = check_cancel_park(r.log, input);
    if (!retracted && r.result.err.find("not sent yet are left out") != std::string::npos) ++left_out;
  }
  CHECK(left_out > 0);  // the case this test is for did happen (commands left out, nothing retracted)
}

TEST_CASE("gc-send: a first Ctrl-C is a cancel: safe end, exit 0", "[gc-send][pause]") {
  const std::string& file = pause_pieces();
  std::string dir = gctest::temp_dir();
  std::string log = dir + "/executed.log";
  // The interrupt comes once the printer has run 500 of the print's
  // commands (an interrupt before gc-send set its handler would kill it).
  auto r = gctest::run(quote(tool_path("gc-send")) + " --no-control --bed 250x210 --port virtual:time-scale=20,heat-rate=1000,log=" +
                       log + " " + quote(file) + " & p=$!\n" +
                       gctest::wait_for_lines(quote(log), {.match = gctest::numbered_log_line(), .at_least = "500", .while_alive = "$p"}) +
                       "kill -INT $p; wait $p");
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(r.err.find("interrupted: cancelling") != std::string::npos);
  auto executed = gctest::parse_executed_log(gctest::read_file(log));
  REQUIRE(executed.commands.size() > 5);
  CHECK(executed.commands.back() == "M400");
  CHECK(executed.commands[executed.commands.size() - 2] == "M84");
}

TEST_CASE("gc-send: commands typed while paused are put back before the resume, and speed F scales what follows",
          "[gc-send][pause]") {
  const std::string& file = pause_pieces();
  auto input = gctest::commands_of(gctest::read_file(file));
  PauseRun r = send_with_control(
      file, "time-scale=20,instant-moves,heat-rate=1000", "--no-pace",
      "at_layer 1; echo pause now > \"$F\"; paused; printf 'gcode G91\\ngcode G1 X5 Y-7 Z3 F600\\ngcode M83\\n"
      "gcode G1 E4 F300\\ngcode M104 S180\\n' > \"$F\"; echo resume > \"$F\"; echo speed 2 > \"$F\"");
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  std::uint64_t last = static_cast<std::uint64_t>(number_after(r.result.err, "pause block sent after input line "));
  Checked c = check_one_pause(r.log, input, last, true);
  gcode::MachineState before = state_after(r.log, c.prefix);
  gcode::MachineState after = state_after(r.log, c.prefix + c.block);
  // The typed commands were executed while paused ...
  std::size_t typed = 0;
  for (std::size_t i = c.prefix; i < c.prefix + c.block; ++i)
    typed += r.log[i].command == "G1 X5 Y-7 Z3 F600" || r.log[i].command == "G1 E4 F300" ? 1 : 0;
  CHECK(typed == 2);
  // ... and the print went on from exactly where it stopped.
  for (int a : {gcode::kX, gcode::kY, gcode::kZ, gcode::kE}) CHECK(after.at(a) == before.at(a));
  CHECK(after.relative_xyz == before.relative_xyz);
  CHECK(after.relative_e == before.relative_e);
  CHECK(after.feedrate == before.feedrate);
  CHECK(after.hotend_target[0] == before.hotend_target[0]);
  // speed 2: from some move on, every extruding move runs at twice its speed
  // (retractions, wipes and Z moves keep theirs, as in gc-speedup): once 20 in a
  // row were doubled, all the rest are.
  gcode::MachineState sent = after, original;
  for (std::size_t i = 0; i < c.prefix; ++i) original.apply(gcode::Line::parse(input[i].text));
  std::size_t doubled = 0, run = 0, plain_after = 0;
  for (std::size_t i = c.prefix; i < input.size(); ++i) {
    gcode::Move got = sent.apply(gcode::Line::parse(r.log[i + c.block].command));
    gcode::Move was = original.apply(gcode::Line::parse(input[i].text));
    if (!was.extruding || was.z_changed || was.xy_length <= 0) continue;
    bool twice = std::fabs(got.feedrate - 2 * was.feedrate) < 1;
    if (run < 20) {
      run = twice ? run + 1 : 0;
    } else if (twice) {
      ++doubled;
    } else {
      ++plain_after;
    }
  }
  CHECK(doubled > 100);
  CHECK(plain_after == 0);
}

TEST_CASE("gc-send: insert FILE while paused prints its moves, then the resume returns exactly", "[gc-send][pause]") {
  const std::string& file = pause_pieces();
  auto input = gctest::commands_of(gctest::read_file(file));
  std::string extra = gctest::temp_dir() + "/tab.gcode";
  // A small square on the top surface, in absolute E from its own origin.
  gctest::write_file(extra, "; a tab\nG90\nM82\nG92 E0\nG1 X100 Y100 F3000\nG1 X105 Y100 E0.2 F1200\nG1 X105 Y105 E0.4\n"
                            "G1 X100 Y105 E0.6\n@pause\nG1 X100 Y100 E0.8\n");
  PauseRun r = send_with_control(file, "time-scale=20,instant-moves,heat-rate=1000", "--no-pace",
                                 "at_layer 2; echo pause > \"$F\"; paused; echo insert " + quote(extra) +
                                     " > \"$F\"; echo insert /nonexistent > \"$F\"; echo resume > \"$F\"");
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  CHECK(r.result.err.find("insert /nonexistent: no such file") != std::string::npos);
  std::uint64_t last = static_cast<std::uint64_t>(number_after(r.result.err, "pause block sent after input line "));
  Checked c = check_one_pause(r.log, input, last);
  std::size_t tab = 0;
  for (std::size_t i = c.prefix; i < c.prefix + c.block; ++i)
    tab += r.log[i].command.rfind("G1 X105", 0) == 0 || r.log[i].command == "G1 X100 Y100 E0.8" ? 1 : 0;
  CHECK(tab == 3);
  gcode::MachineState before = state_after(r.log, c.prefix);
  gcode::MachineState after = state_after(r.log, c.prefix + c.block);
  for (int a : {gcode::kX, gcode::kY, gcode::kZ, gcode::kE}) CHECK(after.at(a) == before.at(a));
  CHECK(after.relative_e == before.relative_e);
  CHECK(after.feedrate == before.feedrate);
}

TEST_CASE("gc-send: a pause asked in the start code comes right before layer 1", "[gc-send][pause]") {
  const std::string& file = pause_pieces();
  std::string text = gctest::read_file(file);
  auto input = gctest::commands_of(text);
  auto layer = layers_of(text);
  PauseRun r = send_with_control(file, "time-scale=20,instant-moves,heat-rate=1000", "--no-pace",
                                 "echo pause > \"$F\"; paused; echo resume > \"$F\"");
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  CHECK(r.result.err.find("pause: pausing before layer 1") != std::string::npos);
  std::uint64_t last = static_cast<std::uint64_t>(number_after(r.result.err, "pause block sent after input line "));
  Checked c = check_one_pause(r.log, input, last);
  REQUIRE(c.prefix < input.size());
  CHECK(layer[input[c.prefix - 1].source_line] == 0);
  CHECK(layer[input[c.prefix].source_line] == 1);
}

// The pause and resume blocks of a run without a park position, split at
// the wait: the lines the printer ran before it and after it.
struct Unparked {
  std::vector<Executed> pause, resume;
};

Unparked split_at_wait(const std::vector<Executed>& log, const Checked& c) {
  Unparked u;
  std::size_t split = c.prefix;
  double longest = -1;
  for (std::size_t i = c.prefix; i < c.prefix + c.block; ++i) {
    double gap = log[i + 1].time - log[i].time;
    if (gap > longest) {
      longest = gap;
      split = i + 1;
    }
  }
  u.pause.assign(log.begin() + static_cast<std::ptrdiff_t>(c.prefix), log.begin() + static_cast<std::ptrdiff_t>(split));
  u.resume.assign(log.begin() + static_cast<std::ptrdiff_t>(split),
                  log.begin() + static_cast<std::ptrdiff_t>(c.prefix + c.block));
  return u;
}

TEST_CASE("gc-send: a pause on a file without a bed retracts and lifts where it is, then returns exactly",
          "[gc-send][pause]") {
  // The cut fixture has lost its settings: no bed, no height. --max-z 1 (the
  // printer's height) in the second run stops the lift below the usual 2 mm.
  const std::string& file = pause_pieces();
  auto input = gctest::commands_of(gctest::read_file(file));
  for (const char* max_z : {"", "--max-z 1"}) {
    INFO("options: " << max_z);
    PauseRun r = send_with_control(file, "time-scale=20,instant-moves,heat-rate=1000",
                                   std::string("--no-pace ") + max_z,
                                   "at_layer 1; echo pause > \"$F\"; paused; sleep 0.3; echo resume > \"$F\"", "");
    INFO(r.result.err);
    REQUIRE(r.result.status == 0);
    CHECK(r.result.err.find("cannot park") == std::string::npos);
    CHECK(r.result.err.find("no park position (the file does not say how big the bed is") != std::string::npos);
    std::uint64_t last = static_cast<std::uint64_t>(number_after(r.result.err, "pause block sent after input line "));
    Checked c = check_one_pause(r.log, input, last);
    REQUIRE(c.block >= 2);
    Unparked u = split_at_wait(r.log, c);
    // While paused nothing ran: the wait is the run's longest gap.
    CHECK(u.resume.front().time - u.pause.back().time >= 0.25);
    gcode::MachineState before = state_after(r.log, c.prefix);
    gcode::MachineState parked = state_after(r.log, c.prefix + u.pause.size());
    gcode::MachineState after = state_after(r.log, c.prefix + c.block);
    // No travel: X and Y never leave the point where the print stopped.
    gcode::MachineState s = before;
    double filament = 0;
    for (const Executed& e : u.pause) {
      filament += s.apply(gcode::Line::parse(e.command)).filament;
      CHECK(s.at(gcode::kX) == before.at(gcode::kX));
      CHECK(s.at(gcode::kY) == before.at(gcode::kY));
    }
    CHECK(filament < 0);  // retracted (the file had not) ...
    const double lift = parked.at(gcode::kZ).to_double() - before.at(gcode::kZ).to_double();
    if (*max_z == '\0') {
      CHECK(lift >= 2 - 1e-9);  // ... and lifted by the pause's lift
    } else {
      CHECK(parked.at(gcode::kZ).to_double() == Approx(1));  // no higher than the printer goes
      CHECK(r.result.err.find("the printer's height, Z1, stops it there") != std::string::npos);
    }
    for (int a : {gcode::kX, gcode::kY, gcode::kZ, gcode::kE}) CHECK(after.at(a) == before.at(a));
    CHECK(after.relative_xyz == before.relative_xyz);
    CHECK(after.relative_e == before.relative_e);
    CHECK(after.feedrate == before.feedrate);
  }
}

TEST_CASE("gc-send: a cancel on a file without a bed retracts and lifts before the heaters go off", "[gc-send][pause]") {
  const std::string& file = pause_pieces();
  PauseRun r = send_with_control(file, "time-scale=5,instant-moves,heat-rate=1000", "",
                                 "at_layer 1; echo cancel > \"$F\"", "");
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  CHECK(r.result.err.find("cancel: no park position") != std::string::npos);
  REQUIRE(r.log.size() > 6);
  check_cancel_park(r.log, gctest::commands_of(gctest::read_file(file)));
  // The park is a lift: above where the print stopped.
  gcode::MachineState end = state_after(r.log, r.log.size());
  gcode::MachineState s;
  double highest_printed = 0;
  for (const Executed& e : r.log) {
    gcode::Move m = s.apply(gcode::Line::parse(e.command));
    if (m.extruding) highest_printed = std::max(highest_printed, s.at(gcode::kZ).to_double());
  }
  CHECK(end.at(gcode::kZ).to_double() >= highest_printed + 2 - 1e-9);
}

namespace {

// Issue 23 §1: pacing against a printer twice as fast as gc-send's model,
// measured from the virtual printer's own report against --no-pace in the
// same test, both runs on the same 1500 moves of 0.2 mm from layer 1 on
// (the open-loop pacer starved it about half the print): planner starved
// (% of the print) and gc-send's time, paced and not. On the simulated
// clock (virtual:simulated-clock: gc-send takes 50 us, scattered, each
// time it wakes, and nothing else of the host counts), so the figures are
// the same on a loaded machine; bench/pace-table.sh measures them on the
// wall clock.
struct PaceRuns {
  double paced = 0, unpaced = 0, paced_time = 0, unpaced_time = 0;
};

PaceRuns pace_against_no_pace(const std::string& printer, const std::string& options, double speed = 2) {
  std::string file = gctest::temp_dir() + "/fast.gcode";
  auto made = gctest::run(quote(tool_path("gc-subdivide")) + " --max 0.2 " +
                          quote(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")) +
                          " | awk 'BEGIN { print \"G28\"; print \"G90\"; print \"M83\" } "
                          "/^;LAYER_CHANGE/ { on = 1 } on && k++ < 1500' > " + quote(file));
  REQUIRE(made.status == 0);
  PaceRuns runs;
  for (bool paced : {true, false}) {
    auto r = gctest::run(quote(tool_path("gc-send")) + " " + options + (paced ? "" : " --no-pace") +
                         " --port virtual:simulated-clock,time-scale=5,heat-rate=100000,speed-factor=" +
                         std::to_string(speed) + printer + " " + quote(file));
    INFO(r.err);
    REQUIRE(r.status == 0);
    (paced ? runs.paced : runs.unpaced) = number_after(r.err, "planner starved ");
    const std::size_t summary = r.err.find("summary: lines ");
    REQUIRE(summary != std::string::npos);
    (paced ? runs.paced_time : runs.unpaced_time) = number_after(r.err.substr(summary), ", time ");
  }
  return runs;
}

}  // namespace

TEST_CASE("gc-send pacing: a printer twice as fast that reports ADVANCED_OK is followed, against --no-pace", "[gc-send][pace]") {
  // 9.35 % against 4.45 % starved. (What is left: the learning at the
  // start; the goal is unpaced + 1 %.)
  PaceRuns r = pace_against_no_pace(",advanced-ok", "--flow advanced-ok");
  INFO("planner starved " << r.paced << " % paced, " << r.unpaced << " % with --no-pace");
  CHECK(r.paced <= r.unpaced + 8);
  CHECK(r.paced < 20);
}

TEST_CASE("gc-send pacing: a printer twice as fast without ADVANCED_OK is followed with moves of no length", "[gc-send][pace]") {
  // Marlin's default: the oks say nothing of a planner that is not full; a
  // bare G1 waits for a free block (Planner::_buffer_steps) and is dropped,
  // and its answer says when one was free. (The open-loop pacer starved
  // this printer 49.8 % of the print against 2.3 % unpaced; now 7.86 %
  // against 4.45 %, 1.771 s against 1.729 s: the host's scattered latency
  // costs some learning. The goal, unpaced + 1 %, is
  // bench/pace-table.sh's on a quiet machine.)
  PaceRuns r = pace_against_no_pace("", "");
  INFO("planner starved " << r.paced << " % paced, " << r.unpaced << " % with --no-pace; " << r.paced_time
                          << " s against " << r.unpaced_time << " s");
  CHECK(r.paced <= r.unpaced + 5);
  CHECK(r.paced_time <= 1.05 * r.unpaced_time);
}

TEST_CASE("gc-send pacing: a printer ten times as fast, which the link cannot keep full, is fed as fast as with --no-pace", "[gc-send][pace]") {
  // It drains its 16 blocks faster than 250000 baud refills them; a move
  // per probe's round trip ran at 29 % of --no-pace's rate (117 commands/s
  // against 405), starved 89 % of the print against 44 %. Probes that keep
  // finding room now let up to 16 moves go each: 1.035 s against 1.019 s,
  // 50.4 % against 48.4 % starved (with one move per probe again: 1.307 s,
  // 69.4 %).
  PaceRuns r = pace_against_no_pace("", "", 10);
  INFO("planner starved " << r.paced << " % paced, " << r.unpaced << " % with --no-pace; " << r.paced_time
                          << " s against " << r.unpaced_time << " s");
  CHECK(r.paced_time <= 1.1 * r.unpaced_time);
  CHECK(r.paced <= r.unpaced + 6);
}

TEST_CASE("gc-send pacing: probes go only where the model is in doubt, at most 5 % of the lines at 1 x, 9 % at 2 x, 7 % at 10 x", "[gc-send][pace]") {
  // Issue 41: a probe per held move at the file's pace (5392 for these
  // 5983 lines at 1 x, 441 at 10 x). Probes that come as the model said
  // space the next ones (probe_spacing.hpp): 252 at 1 x, 499 at 2 x, 350
  // at 10 x, each within 1.07 of --no-pace. (At 2 x a probe answered as
  // the model said comes soon after it arrives, and the model's pace is
  // learnt from probes' waits: taken for room, 1596 went.)
  std::string file = gctest::temp_dir() + "/long.gcode";
  auto made = gctest::run(quote(tool_path("gc-subdivide")) + " --max 0.2 " +
                          quote(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode")) +
                          " | awk 'BEGIN { print \"G28\"; print \"G90\"; print \"M83\" } "
                          "/^;LAYER_CHANGE/ { on = 1 } on && k++ < 6000' > " + quote(file));
  REQUIRE(made.status == 0);
  for (double speed : {1.0, 2.0, 10.0}) {
    double seconds[2] = {0, 0};
    for (bool paced : {true, false}) {
      auto r = gctest::run(quote(tool_path("gc-send")) + (paced ? "" : " --no-pace") +
                           " --port virtual:simulated-clock,time-scale=5,heat-rate=100000,speed-factor=" +
                           std::to_string(speed) + " " + quote(file));
      INFO(r.err);
      REQUIRE(r.status == 0);
      const std::string summary = r.err.substr(r.err.find("summary: lines "));
      seconds[paced ? 0 : 1] = number_after(summary, ", time ");
      if (!paced) continue;
      const double lines = number_after(summary, "summary: lines ");
      const double probes = number_after(summary, "pace probes ");
      INFO(probes << " probes for " << lines << " lines at " << speed << " x");
      CHECK(lines > 5900);
      CHECK(probes <= (speed == 1 ? 0.05 : speed == 2 ? 0.09 : 0.07) * lines);
    }
    INFO(seconds[0] << " s paced against " << seconds[1] << " s unpaced at " << speed << " x");
    CHECK(seconds[0] <= 1.10 * seconds[1]);
  }
}
