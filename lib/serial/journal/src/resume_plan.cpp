#include "gcode/serial/journal/resume_plan.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "gcode/serial/journal/journal_point.hpp"

namespace gcode::serial {

namespace {

// Fills the plan's state and input position from entry `i`; false with a
// refusal when the entry's fields do not read.
bool take_entry(const JournalContents& journal, std::size_t i, ResumePlan& plan) {
  const JournalFields& point = journal.entries[i].point;
  std::string problem;
  if (!read_machine_fields(point, plan.state, problem)) {
    plan.refusal = fmt::format("the journal's record of line {} is incomplete: {}", journal.entries[i].n, problem);
    return false;
  }
  plan.entry = i;
  plan.input_line = point.count("line");
  plan.input_offset = point.count("off");
  plan.layer = static_cast<int>(point.count("layer"));
  plan.paused = point.get("paused") == "1";
  return true;
}

// The index of the entry sent as line n, or npos.
std::size_t index_of(const JournalContents& journal, std::uint64_t n) {
  for (std::size_t i = journal.entries.size(); i-- > 0;)
    if (journal.entries[i].n == n) return i;
  return std::string::npos;
}

std::string position_mismatch(const PositionReport& report, const MachineState& state, double tolerance) {
  static constexpr char kAxes[] = {'X', 'Y', 'Z'};
  const std::array<double, 3> was{state.at(kX).to_double(), state.at(kY).to_double(), state.at(kZ).to_double()};
  const int a = axis_off(report, was, tolerance);
  if (a < 0) return std::string();
  const auto i = static_cast<std::size_t>(a);
  return fmt::format("the printer is at {} {:.3f}, the journal says {:.3f} after that line: it did not keep its "
                     "state (was it reset, or moved by hand?)",
                     kAxes[i], report.axis[i], was[i]);
}

// The height the nozzle stands at after a state (a z-hop's lift left out).
double nozzle_height(const MachineState& s) { return s.lifted ? s.lift_base_z : s.position[kZ]; }

// The printer kept running inside the way back after an earlier reset (`i`:
// one of its lines; `reached`: the machine after the last line of it the
// printer took, `taken` that line's number): the way back is made again, as
// after a reset, to the command it went back to. Until its G92 Z ran the
// nozzle stands where the reset left it (the highest of the moves between
// that command and the way back, as the live resume took it); after, the
// printer's own Z is right.
ResumePlan after_stop_in_way_back(const JournalContents& journal, std::size_t i, const MachineState& reached,
                                  std::uint64_t taken, ResumePlan plan) {
  const std::uint64_t back = journal.entries[i].point.count("restore");
  const std::size_t r = index_of(journal, back);
  if (r == std::string::npos || r >= i) {
    plan.refusal = fmt::format("the journal no longer holds line {}, where an earlier resume went back to", back);
    return plan;
  }
  if (!take_entry(journal, r, plan)) return plan;
  double z_high = nozzle_height(plan.state);
  MachineState s;
  std::string problem;
  for (std::size_t k = r + 1; k < i && journal.entries[k].point.count("restore") != back; ++k)
    if (read_machine_fields(journal.entries[k].point, s, problem)) z_high = std::max(z_high, nozzle_height(s));
  if (reached.known[kZ]) z_high = reached.position[kZ];
  plan.track = read_track_fields(journal.entries[r].point, plan.state);
  plan.condition = PrinterCondition::Reset;
  plan.way_back_line = taken;
  plan.primed = reached.known[kE];  // E is known from the prime on
  if (z_high > nozzle_height(plan.state) + 1e-9) plan.nozzle_z = z_high;
  plan.possible = true;
  return plan;
}

ResumePlan after_keep_running(const JournalContents& journal, const PrinterFindings& printer,
                              const ResumeLimits& limits, ResumePlan plan) {
  if (printer.expected_line < 1) {
    plan.refusal = "the printer did not say which line it expects next";
    return plan;
  }
  auto last_run = static_cast<std::uint64_t>(printer.expected_line - 1);
  std::size_t i = index_of(journal, last_run);
  if (i == std::string::npos) {
    plan.refusal = fmt::format("the printer took line {} last, which the journal does not hold (lines {} to {})",
                               last_run, journal.entries.front().n, journal.entries.back().n);
    return plan;
  }
  if (!take_entry(journal, i, plan)) return plan;
  if (journal.entries[i].point.count("restore") != 0)
    return after_stop_in_way_back(journal, i, plan.state, last_run, plan);
  // It took the way back's handshake (M110 numbered on from line i: the
  // printer had reset) and none of its lines.
  if (i + 1 < journal.entries.size() && journal.entries[i + 1].point.count("restore") != 0)
    return after_stop_in_way_back(journal, i + 1, MachineState{}, last_run, plan);
  if (printer.position) {
    plan.refusal = position_mismatch(*printer.position, plan.state, limits.position_tolerance);
    if (!plan.refusal.empty()) return plan;
  }
  plan.possible = true;
  return plan;
}

bool is_move(const MachineState& before, const MachineState& after) {
  return before.exact != after.exact;
}

double distance(const MachineState& a, const MachineState& b) {
  double dx = a.position[kX] - b.position[kX], dy = a.position[kY] - b.position[kY],
         dz = a.position[kZ] - b.position[kZ];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

ResumePlan lost_before(std::uint64_t n, ResumePlan& plan) {
  plan.refusal = fmt::format("the journal no longer holds the lines before line {}, among those the printer may have "
                             "lost: where to go back to is not known",
                             n);
  return plan;
}

ResumePlan after_reset(const JournalContents& journal, const ResumeLimits& limits, ResumePlan plan) {
  if (!limits.can_home_xy_alone) {
    MachineState last;
    std::string problem;
    read_machine_fields(journal.entries.back().point, last, problem);
    plan.refusal = xy_homing_refusal(last.position[kZ], journal.header.get("regular") == "1" ? journal.header.get("input") : "-");
    return plan;
  }
  std::size_t acked = journal.acknowledged > 0 ? index_of(journal, journal.acknowledged) : std::string::npos;
  if (acked == std::string::npos && journal.acknowledged > 0) {
    // Going back from the newest line instead could skip what never ran.
    plan.refusal = fmt::format("the journal no longer holds line {}, the last the printer acknowledged: where to go "
                               "back to is not known",
                               journal.acknowledged);
    return plan;
  }
  if (acked == std::string::npos) acked = journal.entries.size() - 1;
  // Walk back over the newest planner_blocks acknowledged moves: the last
  // one that surely ran is the entry before the oldest of them.
  std::size_t i = acked;
  if (!take_entry(journal, i, plan)) return plan;
  MachineState after = plan.state, before;
  std::string problem;
  int moves = 0;
  double mm = 0, z_high = nozzle_height(after);
  bool surely_ran = false;  // stopped at a command after which nothing before it was pending
  while (i > 0 && moves < limits.planner_blocks) {
    if (std::uint64_t back = journal.entries[i].point.count("restore"); back != 0) {
      // A line of an earlier resume after a reset: that resume starts again.
      i = index_of(journal, back);
      if (i == std::string::npos) {
        plan.refusal = fmt::format("the journal no longer holds line {}, where an earlier resume went back to", back);
        return plan;
      }
      surely_ran = true;
      break;
    }
    if (is_drained(journal.entries[i].point)) {
      surely_ran = true;
      break;
    }
    if (journal.entries[i - 1].n + 1 != journal.entries[i].n) return lost_before(journal.entries[i].n, plan);
    if (!read_machine_fields(journal.entries[i - 1].point, before, problem)) break;
    if (is_move(before, after)) {
      ++moves;
      mm += distance(before, after);
      z_high = std::max(z_high, nozzle_height(after));
    }
    after = before;
    --i;
  }
  // (The loop stops before looking at the oldest line.)
  surely_ran = surely_ran || is_drained(journal.entries[i].point);
  // Short of the planner's moves at the journal's oldest line: the lines
  // before it, which the printer may have lost, are no longer held.
  if (i == 0 && !surely_ran && moves < limits.planner_blocks && journal.entries[0].n > 1)
    return lost_before(journal.entries[0].n, plan);
  if (!take_entry(journal, i, plan)) return plan;
  plan.track = read_track_fields(journal.entries[i].point, plan.state);
  if (plan.track.top_z <= 0) {
    plan.refusal = "the printer reset before anything was printed: start the print again";
    return plan;
  }
  if (z_high > nozzle_height(plan.state)) plan.nozzle_z = z_high;
  plan.redone_moves = moves;
  plan.redone_mm = mm;
  plan.possible = true;
  return plan;
}

}  // namespace

ResumePlan plan_resume(const JournalContents& journal, const PrinterFindings& printer, const ResumeLimits& limits) {
  ResumePlan plan;
  plan.condition = printer.condition;
  if (journal.finished) {
    plan.refusal = "the journal's print ended normally: nothing to resume";
    return plan;
  }
  if (journal.entries.empty()) {
    plan.refusal = "the journal holds no command: the print had not begun (start it again)";
    return plan;
  }
  if (printer.condition == PrinterCondition::KeptRunning) return after_keep_running(journal, printer, limits, plan);
  return after_reset(journal, limits, plan);
}

}  // namespace gcode::serial
