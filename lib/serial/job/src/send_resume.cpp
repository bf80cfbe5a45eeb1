#include "gcode/serial/job/send_resume.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "gcode/serial/job/printer_probe.hpp"
#include "gcode/serial/job/send_session.hpp"
#include "gcode/serial/journal/input_identity.hpp"
#include "gcode/serial/journal/journal_header.hpp"
#include "gcode/serial/journal/journal_point.hpp"

namespace gcode::serial {

namespace {

// A shell word: quoted only where it needs it.
std::string shell_word(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789/._-+:,=@") ==
                        std::string::npos)
    return s;
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The print stood paused (its pause block had gone out, or some of it): the
// printer is taken to where the block left it, and the print waits for
// `resume` there (the control sends what of the block had not run). The
// stop is the newest command of the input before the block. A printer that
// kept running and took none of the block goes on with the print.
void into_pause(const JournalContents& journal, ResumeStart& r) {
  const std::vector<JournalEntry>& entries = journal.entries;
  std::size_t stop = entries.size();
  while (stop > 0 && entries[stop - 1].point.get("own") == "1") --stop;
  if (stop == 0) throw ResumeError("cannot resume: the journal holds the pause block but not where the print stopped");
  ResumePlan& plan = r.plan;
  std::string problem;
  if (plan.condition == PrinterCondition::KeptRunning && plan.entry < stop) {
    r.pause_not_begun = true;
    return;
  }
  ResumeStart::Paused paused;
  // Kept running: the lines of the block the printer took; a reset: those
  // the journal holds (the resume sequence takes the head where they left it).
  // (gc-send's questions and pace probes among them, "ask", are none of the block's.)
  const std::size_t through = plan.condition == PrinterCondition::KeptRunning ? plan.entry + 1 : entries.size();
  paused.taken = 0;
  for (std::size_t i = stop; i < through; ++i) paused.taken += entries[i].point.get("ask") == "1" ? 0 : 1;
  if (!read_machine_fields(entries[stop - 1].point, paused.at, problem))
    throw ResumeError(fmt::format("cannot resume: the journal's record of where the print paused is incomplete: {}",
                                  problem));
  paused.track = read_track_fields(entries[stop - 1].point, paused.at);
  if (plan.condition == PrinterCondition::Reset) {
    // Back to the parked head, whichever of the block's lines ran: Z is
    // declared at the highest height the block took it to.
    plan.entry = entries.size() - 1;
    MachineState parked;
    if (!read_machine_fields(entries.back().point, parked, problem))
      throw ResumeError(fmt::format("cannot resume: the journal's record of the pause block is incomplete: {}", problem));
    double high = paused.at.position[kZ];
    for (std::size_t i = stop; i < entries.size(); ++i) {
      MachineState s;
      if (read_machine_fields(entries[i].point, s, problem)) high = std::max(high, s.position[kZ]);
    }
    plan.state = parked;
    plan.nozzle_z = high > parked.position[kZ] ? high : std::numeric_limits<double>::quiet_NaN();
    plan.track = ResumeTrack{paused.track.top_z, 0, 0};  // the filament is where the block left it
    plan.redone_moves = 0;
    plan.redone_mm = 0;
    r.last = static_cast<long long>(entries.back().n);
    r.point = entries.back().point;
  }
  plan.input_line = entries[stop - 1].point.count("line");
  plan.input_offset = entries[stop - 1].point.count("off");
  plan.layer = static_cast<int>(entries[stop - 1].point.count("layer"));
  r.paused = paused;
}

// The printer took the journal's last line: it answered it, or it ran on
// and expects the line after it.
bool took_last(const JournalContents& journal, const PrinterFindings& printer) {
  const JournalEntry& last = journal.entries.back();
  if (journal.acknowledged >= last.n) return true;
  return printer.condition == PrinterCondition::KeptRunning &&
         printer.expected_line == static_cast<long long>(last.n) + 1;
}

// Why nothing is left to send, or "". gc-send stopped
//  * while a cancel's end went out (its lines, numbered at once, carry the
//    state cancelling): the print is over, never to go on; refused when
//    the printer took only part of it (its heaters may be on);
//  * inside its closing block, the M400 numbered once every line of the
//    input was (field end), and the printer took it (its ok comes once the
//    planner is empty: a reset after it lost nothing).
std::string nothing_left(const JournalContents& journal, const PrinterFindings& printer) {
  const JournalEntry& last = journal.entries.back();
  if (last.point.get("state") == "cancelling") {
    if (printer.condition == PrinterCondition::Reset)
      return "the print was being cancelled when gc-send stopped, and the printer reset since (its heaters are off)";
    if (took_last(journal, printer))
      return fmt::format("the print was cancelled: the printer had taken the whole of the cancel's end (to line {}) "
                         "when gc-send stopped",
                         last.n);
    throw ResumeError(fmt::format("cannot resume: the print was being cancelled when gc-send stopped, and the printer "
                                  "took its end only to line {} of {}: nothing to resume, but its heaters may still "
                                  "be on (M104 S0 and M140 S0 turn them off)",
                                  printer.expected_line - 1, last.n));
  }
  if (last.point.get("end") == "1" && took_last(journal, printer))
    return fmt::format("the print is complete: the printer had taken every line of the input and gc-send's closing "
                       "M400 (line {}) when gc-send stopped",
                       last.n);
  return std::string();
}

}  // namespace

ResumeSource open_resume(const std::string& journal_path, const std::string& file) {
  ResumeSource s;
  try {
    s.journal = read_journal(journal_path);
  } catch (const JournalError& e) {
    throw ResumeError(fmt::format("cannot resume: {}", e.what()));
  }
  if (s.journal.finished)
    throw ResumeError(fmt::format("cannot resume: the print of {} ended normally (nothing to resume)", journal_path));
  s.resolved = file;
  if (s.resolved.empty()) s.resolved = s.journal.header.get("regular") == "1" ? s.journal.header.get("input") : "-";
  return s;
}

void check_resume_input(const ResumeSource& source, const std::string& name, int fd) {
  std::string problem = input_mismatch(source.journal.header, identify_input(name, fd));
  if (!problem.empty()) throw ResumeError(fmt::format("cannot resume: {}", problem));
}

ResumeStart begin_resume(const ResumeSource& source, const ProbeResult& probe, SendSession& session,
                         const ResumeLimits& limits) {
  if (!probe.problem.empty()) throw ResumeError(fmt::format("cannot resume: {}", probe.problem));
  ResumeStart r;
  r.greeted = probe.greeted;
  r.complete = nothing_left(source.journal, probe.findings);
  if (!r.complete.empty()) {
    r.last = static_cast<long long>(source.journal.entries.back().n);
    r.point = source.journal.entries.back().point;
    return r;
  }
  r.plan = plan_resume(source.journal, probe.findings, limits);
  if (!r.plan.possible) throw ResumeError(fmt::format("cannot resume: {}", r.plan.refusal));
  const JournalEntry& from = source.journal.entries[r.plan.entry];
  r.last = static_cast<long long>(from.n);
  r.point = from.point;
  // The objects cancelled by the time gc-send stopped (the journal's last
  // line's: a cancel asked after the command the print goes on after counts
  // too) are left out from where the print goes on.
  if (const std::string* cancelled = source.journal.entries.back().point.find("cancelled"))
    r.point.set("cancelled", *cancelled);
  r.next = probe.findings.expected_line;
  if (r.plan.condition == PrinterCondition::Reset) {
    // Numbered on after every number the journal used: one names one command.
    std::uint64_t highest = 0;
    for (const JournalEntry& e : source.journal.entries) highest = std::max(highest, e.n);
    r.next = static_cast<long long>(highest) + 1;
  }
  if (source.journal.entries.back().point.get("paused") == "1") into_pause(source.journal, r);
  if (r.point.get("own") == "1" && !r.paused)
    throw ResumeError(fmt::format("cannot resume: the printer stopped inside a block of gc-send's own (line {}, state "
                                  "{}), not at a line of the input",
                                  r.last, r.point.get("state")));
  if (!r.point.get("swap").empty())
    throw ResumeError("cannot resume: the print had swapped to another file (a resume of a swap is not done yet)");
  std::uint64_t hoff = r.point.count("hoff");
  session.skip_printed(r.plan.input_offset, hoff, r.plan.input_line, r.plan.layer, r.paused ? r.paused->at : r.plan.state);
  if (session.skipped_bytes() < r.plan.input_offset)
    throw ResumeError(fmt::format("cannot resume: the input ends after {} bytes, before the {} printed",
                                  session.skipped_bytes(), r.plan.input_offset));
  if (hoff > 0 && hash_text(session.skipped_hash()) != r.point.get("hash"))
    throw ResumeError(fmt::format("cannot resume: the input is not the one printed (its first {} bytes hash to {}, "
                                  "the journal's to {})",
                                  hoff, hash_text(session.skipped_hash()), r.point.get("hash")));
  return r;
}

std::vector<JournalEntry> carried_entries(const ResumeSource& source, const ResumeStart& start) {
  std::vector<JournalEntry> carried;
  for (const JournalEntry& e : source.journal.entries)
    if (e.n < static_cast<std::uint64_t>(start.last)) carried.push_back(e);
  carried.push_back(JournalEntry{static_cast<std::uint64_t>(start.last), start.point});
  // Every command up to it ran: the printer had drained its queue when it
  // was asked where it is, or it reset and the resume goes back to this one.
  // A reset later walks back no further.
  mark_drained(carried.back().point);
  return carried;
}

std::string resume_command(const std::string& journal, const std::string& input, const std::string& port) {
  std::string command = fmt::format("gc-send --resume {} {} --port {}", shell_word(journal),
                                    input == "-" ? std::string("-") : shell_word(input), shell_word(port));
  // A stream: the same pipeline, run the same way, into it.
  return input == "-" ? "(the same pipeline) | " + command : command;
}

}  // namespace gcode::serial
