#include "gcode/serial/send_resume.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "gcode/serial/input_identity.hpp"
#include "gcode/serial/journal_header.hpp"
#include "gcode/serial/printer_probe.hpp"
#include "gcode/serial/send_session.hpp"

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
  if (s.journal.entries.empty())
    throw ResumeError(fmt::format("cannot resume: {} holds no command (the print had not begun: start it again)",
                                  journal_path));
  s.resolved = file;
  if (s.resolved.empty()) s.resolved = s.journal.header.get("regular") == "1" ? s.journal.header.get("input") : "-";
  return s;
}

void check_resume_input(const ResumeSource& source, const std::string& name, int fd) {
  std::string problem = input_mismatch(source.journal.header, identify_input(name, fd));
  if (!problem.empty()) throw ResumeError(fmt::format("cannot resume: {}", problem));
}

ResumeStart begin_resume(const ResumeSource& source, int port_fd, SendSession& session, double timeout,
                         const ResumeLimits& limits, const std::function<void(std::string_view)>& trace) {
  ProbeResult probe = probe_printer(port_fd, timeout, trace);
  if (!probe.problem.empty()) throw ResumeError(fmt::format("cannot resume: {}", probe.problem));
  ResumeStart r;
  r.greeted = probe.greeted;
  r.plan = plan_resume(source.journal, probe.findings, limits);
  if (!r.plan.possible) throw ResumeError(fmt::format("cannot resume: {}", r.plan.refusal));
  const JournalEntry& from = source.journal.entries[r.plan.entry];
  r.last = static_cast<long long>(from.n);
  r.point = from.point;
  r.next = probe.findings.expected_line;
  if (r.plan.condition == PrinterCondition::Reset) {
    // Numbered on after every number the journal used: one names one command.
    std::uint64_t highest = 0;
    for (const JournalEntry& e : source.journal.entries) highest = std::max(highest, e.n);
    r.next = static_cast<long long>(highest) + 1;
  }
  if (r.plan.paused)
    throw ResumeError("cannot resume: the print was paused when it stopped (a resume into the pause is not done yet)");
  if (r.point.get("own") == "1")
    throw ResumeError(fmt::format("cannot resume: the printer stopped inside a block of gc-send's own (line {}, state "
                                  "{}), not at a line of the input",
                                  r.last, r.point.get("state")));
  if (!r.point.get("swap").empty())
    throw ResumeError("cannot resume: the print had swapped to another file (a resume of a swap is not done yet)");
  std::uint64_t hoff = r.point.count("hoff");
  session.skip_printed(r.plan.input_offset, hoff, r.plan.input_line, r.plan.layer, r.plan.state);
  if (session.skipped_bytes() < r.plan.input_offset)
    throw ResumeError(fmt::format("cannot resume: the input ends after {} bytes, before the {} printed",
                                  session.skipped_bytes(), r.plan.input_offset));
  if (hoff > 0 && hash_text(session.skipped_hash()) != r.point.get("hash"))
    throw ResumeError(fmt::format("cannot resume: the input is not the one printed (its first {} bytes hash to {}, "
                                  "the journal's to {})",
                                  hoff, hash_text(session.skipped_hash()), r.point.get("hash")));
  return r;
}

std::string resume_command(const std::string& journal, const std::string& input, const std::string& port) {
  std::string command = fmt::format("gc-send --resume {} {} --port {}", shell_word(journal),
                                    input == "-" ? std::string("-") : shell_word(input), shell_word(port));
  // A stream: the same pipeline, run the same way, into it.
  return input == "-" ? "(the same pipeline) | " + command : command;
}

}  // namespace gcode::serial
