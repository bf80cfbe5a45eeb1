// Where a print goes on after a fault (gcode/serial/journal/resume_plan.hpp), on
// the journal of a real print: a printer that kept running goes on right
// after the line before the one it expects, once its position agrees; a
// printer that reset goes back over the moves its planner may have lost.
#include <catch2/catch.hpp>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/serial/job/send_resume.hpp"
#include "gcode/serial/journal/journal_point.hpp"
#include "gcode/serial/journal/resume_plan.hpp"
#include "test_support.hpp"

using namespace gcode;
using namespace gcode::serial;

namespace {

struct Print {
  JournalContents journal;
  std::vector<MachineState> states;  // after command i+1
};

// The journal a print of the fixture leaves: one entry per command, its
// input line and offset, acknowledged up to `acked`.
Print print_of(const std::string& fixture, std::uint64_t acked) {
  Print p;
  std::string text = gctest::read_file(gctest::fixture_path(fixture));
  MachineState state = gctest::initial_state(text);
  std::uint64_t line_no = 0, offset = 0;
  for (const std::string& raw : gctest::split_lines(text)) {
    ++line_no;
    offset += raw.size();
    std::string_view code = raw;
    while (!code.empty() && (code.back() == '\n' || code.back() == '\r')) code.remove_suffix(1);
    Line line = Line::parse(code);
    if (line.kind == CommandKind::None) continue;
    state.apply(line);
    JournalEntry e;
    e.n = p.states.size() + 1;
    write_machine_fields(state, e.point);
    e.point.set("line", std::to_string(line_no));
    e.point.set("off", std::to_string(offset));
    p.journal.entries.push_back(std::move(e));
    p.states.push_back(state);
  }
  p.journal.acknowledged = acked;
  return p;
}

PositionReport at(const MachineState& s, double dx = 0) {
  PositionReport r;
  for (int a = 0; a < 4; ++a) {
    r.axis[static_cast<std::size_t>(a)] = s.at(a).to_double() + (a == 0 ? dx : 0);
    r.present[static_cast<std::size_t>(a)] = true;
  }
  return r;
}

}  // namespace

TEST_CASE("resume plan: a printer that kept running goes on after its last line", "[serial][journal]") {
  Print p = print_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 3000);
  PrinterFindings kept{PrinterCondition::KeptRunning, 3001, at(p.states[2999])};
  serial::ResumePlan plan = plan_resume(p.journal, kept, {});
  REQUIRE(plan.possible);
  CHECK(plan.entry == 2999);
  CHECK(same_machine(plan.state, p.states[2999]));
  CHECK(plan.input_line == std::stoull(p.journal.entries[2999].point.get("line")));
  CHECK(plan.input_offset == std::stoull(p.journal.entries[2999].point.get("off")));
  CHECK(plan.redone_mm == 0);

  // Lines sent but not acknowledged before the kill still ran: the printer says so.
  PrinterFindings further{PrinterCondition::KeptRunning, 3006, at(p.states[3004])};
  serial::ResumePlan later = plan_resume(p.journal, further, {});
  REQUIRE(later.possible);
  CHECK(later.entry == 3004);

  PrinterFindings moved{PrinterCondition::KeptRunning, 3001, at(p.states[2999], 0.05)};
  serial::ResumePlan refused = plan_resume(p.journal, moved, {});
  CHECK_FALSE(refused.possible);
  CHECK(refused.refusal.find("the printer is at X") == 0);

  PrinterFindings unknown{PrinterCondition::KeptRunning, 999999, std::nullopt};
  CHECK(plan_resume(p.journal, unknown, {}).refusal.find("does not hold") != std::string::npos);
}

TEST_CASE("resume plan: after a reset, back over the moves the planner may have lost", "[serial][journal]") {
  Print p = print_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 5000);
  ResumeLimits limits;
  limits.planner_blocks = 16;
  serial::ResumePlan plan = plan_resume(p.journal, {PrinterCondition::Reset, -1, std::nullopt}, limits);
  REQUIRE(plan.possible);
  CHECK(plan.redone_moves == 16);
  CHECK(plan.entry < 4999);
  // Exactly the moves between the plan's state and the acknowledged line.
  int moves = 0;
  double mm = 0;
  for (std::size_t i = plan.entry; i < 4999; ++i) {
    const MachineState& a = p.states[i];
    const MachineState& b = p.states[i + 1];
    if (a.exact == b.exact) continue;
    ++moves;
    mm += std::hypot(b.position[kX] - a.position[kX], b.position[kY] - a.position[kY], b.position[kZ] - a.position[kZ]);
  }
  CHECK(moves == 16);
  CHECK(plan.redone_mm == Approx(mm));
  CHECK(plan.redone_mm > 0);
  CHECK(same_machine(plan.state, p.states[plan.entry]));

  limits.can_home_xy_alone = false;
  serial::ResumePlan delta = plan_resume(p.journal, {PrinterCondition::Reset, -1, std::nullopt}, limits);
  CHECK_FALSE(delta.possible);
  CHECK(delta.refusal.find("cannot home X and Y") != std::string::npos);
}

TEST_CASE("resume plan: after a reset, a journal that lost the lines to go back over is refused, not guessed",
          "[serial][journal]") {
  ResumeLimits limits;
  limits.planner_blocks = 16;
  // The acknowledged line itself is gone: going back from the newest line
  // (as it once did) would skip every line between them.
  Print p = print_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 5000);
  p.journal.entries.erase(p.journal.entries.begin() + 4999);
  serial::ResumePlan plan = plan_resume(p.journal, {PrinterCondition::Reset, -1, std::nullopt}, limits);
  CHECK_FALSE(plan.possible);
  CHECK(plan.refusal.find("no longer holds line 5000, the last the printer acknowledged") != std::string::npos);
  // A gap among the moves the planner may have lost.
  Print q = print_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 5000);
  q.journal.entries.erase(q.journal.entries.begin() + 4995);
  plan = plan_resume(q.journal, {PrinterCondition::Reset, -1, std::nullopt}, limits);
  CHECK_FALSE(plan.possible);
  CHECK(plan.refusal.find("no longer holds the lines before line 4997") != std::string::npos);
  // The journal starts a few lines before the acknowledged one.
  Print r = print_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 5000);
  r.journal.entries.erase(r.journal.entries.begin(), r.journal.entries.begin() + 4990);
  plan = plan_resume(r.journal, {PrinterCondition::Reset, -1, std::nullopt}, limits);
  CHECK_FALSE(plan.possible);
  CHECK(plan.refusal.find("no longer holds the lines before line 4991") != std::string::npos);
}

TEST_CASE("resume plan: after a reset, the walk back stops at a command after which nothing was pending",
          "[serial][journal]") {
  ResumeLimits limits;
  limits.planner_blocks = 16;
  // Moves between two entries: the plan redoes exactly those.
  auto moves_between = [](const Print& p, std::size_t from, std::size_t to) {
    int moves = 0;
    for (std::size_t i = from; i < to; ++i) moves += p.states[i].exact != p.states[i + 1].exact ? 1 : 0;
    return moves;
  };
  // An M400 answered a few moves before the acknowledged line: the
  // planner held only what came after it.
  Print p = print_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 5000);
  mark_drained(p.journal.entries[4994].point);
  serial::ResumePlan plan = plan_resume(p.journal, {PrinterCondition::Reset, -1, std::nullopt}, limits);
  REQUIRE(plan.possible);
  CHECK(plan.entry == 4994);
  CHECK(plan.redone_moves == moves_between(p, 4994, 4999));
  CHECK(plan.redone_moves < 16);
  // The acknowledged line itself drained: nothing is redone.
  mark_drained(p.journal.entries[4999].point);
  plan = plan_resume(p.journal, {PrinterCondition::Reset, -1, std::nullopt}, limits);
  REQUIRE(plan.possible);
  CHECK(plan.entry == 4999);
  CHECK(plan.redone_moves == 0);
  // A journal that starts at a drained line holds all a walk back needs.
  Print q = print_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 5000);
  q.journal.entries.erase(q.journal.entries.begin(), q.journal.entries.begin() + 4994);
  mark_drained(q.journal.entries[0].point);
  plan = plan_resume(q.journal, {PrinterCondition::Reset, -1, std::nullopt}, limits);
  REQUIRE(plan.possible);
  CHECK(plan.entry == 0);
  CHECK(same_machine(plan.state, p.states[4994]));
}

TEST_CASE("resume plan: the journal of a resumed print, killed before it wrote a line of its own, resumes again",
          "[serial][journal]") {
  // gc-send --resume replaced the old journal and was killed at once (the
  // soak test found it): the new journal must still say where the print is,
  // and a printer that resets then must go back to where that resume went
  // on, no further (its moves before had run: the resume's M400).
  ResumeLimits limits;
  limits.planner_blocks = 16;
  Print p = print_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 3000);
  for (PrinterCondition first : {PrinterCondition::KeptRunning, PrinterCondition::Reset}) {
    INFO((first == PrinterCondition::Reset ? "the first resume after a reset" : "the first resume after a kill"));
    ResumeSource old{p.journal, ""};
    PrinterFindings found{first, first == PrinterCondition::Reset ? -1 : 3001,
                          first == PrinterCondition::Reset ? std::nullopt : std::optional(at(p.states[2999]))};
    ResumeStart start;
    start.plan = plan_resume(old.journal, found, limits);
    REQUIRE(start.plan.possible);
    start.last = static_cast<long long>(p.journal.entries[start.plan.entry].n);
    start.point = p.journal.entries[start.plan.entry].point;
    std::vector<JournalEntry> carried = carried_entries(old, start);
    REQUIRE(carried.back().n == static_cast<std::uint64_t>(start.last));
    CHECK(carried.size() == start.plan.entry + 1);  // nothing after the line it goes on after

    std::string path = gctest::temp_dir() + "/resumed.journal";
    { JournalWriter w({path}, old.journal.header, carried); }  // killed before its first flush
    JournalContents now = read_journal(path);
    REQUIRE_FALSE(now.entries.empty());
    CHECK(now.acknowledged == static_cast<std::uint64_t>(start.last));

    // The printer kept running: on after that line.
    serial::ResumePlan kept = plan_resume(
        now, {PrinterCondition::KeptRunning, start.last + 1, at(p.states[start.plan.entry])}, limits);
    REQUIRE(kept.possible);
    CHECK(same_machine(kept.state, p.states[start.plan.entry]));
    // It reset: back to that line exactly, nothing redone.
    serial::ResumePlan reset = plan_resume(now, {PrinterCondition::Reset, -1, std::nullopt}, limits);
    INFO(reset.refusal);
    REQUIRE(reset.possible);
    CHECK(same_machine(reset.state, p.states[start.plan.entry]));
    CHECK(reset.redone_moves == 0);
    CHECK(reset.input_line == std::stoull(start.point.get("line")));
  }
}

TEST_CASE("resume plan: a finished or empty journal has nothing to resume", "[serial][journal]") {
  Print p = print_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 100);
  p.journal.finished = true;
  CHECK(plan_resume(p.journal, {}, {}).refusal.find("ended normally") != std::string::npos);
  JournalContents empty;
  CHECK(plan_resume(empty, {}, {}).refusal.find("had not begun") != std::string::npos);
}
