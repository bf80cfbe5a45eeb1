#pragma once
// gc-send --resume: the print a journal holds goes on (issue 22, §4). Before
// the port is opened, the journal is read and the input checked against it
// (open_resume); once connected, the printer is asked where it is, the
// resume planned and the printed part of the input read and checked
// (begin_resume); then the session goes on from the next line exactly.
// Every refusal is a ResumeError with the reason, before anything of the
// print is sent.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/serial/job/printer_probe.hpp"
#include "gcode/serial/journal/journal.hpp"
#include "gcode/serial/journal/resume_plan.hpp"

namespace gcode::serial {

class SendSession;

class ResumeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The old journal, read back and checked: not finished.
// `file`: the input as given ("" = the journal's own file, or standard
// input for a journal of a stream), resolved into `resolved`.
struct ResumeSource {
  JournalContents journal;
  std::string resolved;
  // No command in it: none reached the printer (each is written before its
  // bytes go out), so the print begins from its first line.
  bool not_begun() const { return journal.entries.empty(); }
};
ResumeSource open_resume(const std::string& journal_path, const std::string& file);
// The input opened as `fd` (named `name`, absolute) is the journal's input.
void check_resume_input(const ResumeSource& source, const std::string& name, int fd);

struct ResumeStart {
  ResumePlan plan;
  long long next = 0;      // the protocol line numbered next (kept running: the one the printer expects)
  long long last = 0;      // the journal's number of the command the print goes on after
  JournalFields point;     // the journal's record of it
  bool greeted = false;    // a reset: the printer greeted (else its line numbers were back at 0)
  // The print stood paused: where it stopped (the pipeline goes on from
  // there once resumed) and what it had printed; the plan's state is the
  // parked head's.
  struct Paused {
    MachineState at;
    ResumeTrack track;
    std::size_t taken = 0;  // lines of the pause block that ran (the rest go out again)
  };
  std::optional<Paused> paused;
  // gc-send stopped as the pause block went out, and the printer ran on
  // without taking any of it: the print goes on, not paused.
  bool pause_not_begun = false;
  // Why nothing is left to send ("": the print goes on): the printer had
  // taken gc-send's closing M400 (every line of the input ran), or the
  // print was cancelled. `last` and `point` are the journal's last line's.
  std::string complete;
};

// Plans from what the printer said (`probe`, printer_probe.hpp), and skips
// the printed part of the input in `session` (its hash checked).
// A printer that reset goes on from the plan's command (ResumePlan): the
// caller sends the resume sequence first. A print whose closing M400 the
// printer took, or that was being cancelled, is `complete`: no plan,
// nothing skipped (a cancel the printer took only part of is refused).
ResumeStart begin_resume(const ResumeSource& source, const ProbeResult& probe, SendSession& session,
                         const ResumeLimits& limits);

// What the new journal carries over from the old one: its commands up to
// the one the print goes on after (`start.last`, whose point ends them).
// Written whole before the old file goes, they keep the print resumable
// from the first moment, also after a printer reset that lost moves sent
// before the resume.
std::vector<JournalEntry> carried_entries(const ResumeSource& source, const ResumeStart& start);

// The one command that resumes a print that stopped with the part on the bed.
std::string resume_command(const std::string& journal, const std::string& input, const std::string& port);

}  // namespace gcode::serial
