#include "gcode/serial/job/send_job.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/core/file_io.hpp"
#include "gcode/core/number.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/report/layer_time.hpp"
#include "gcode/serial/control/control_verbs.hpp"
#include "gcode/serial/job/send_resume.hpp"
#include "gcode/serial/job/send_session.hpp"
#include "gcode/serial/journal/input_identity.hpp"
#include "gcode/serial/journal/journal_lock.hpp"
#include "gcode/serial/journal/journal_point.hpp"
#include "gcode/serial/journal/send_journal.hpp"
#include "gcode/serial/link/event_loop.hpp"
#include "gcode/serial/link/port.hpp"

namespace gcode::serial {

namespace {

// "link utilisation 98.5 % (250000 baud)": bytes written against what the
// baud rate could carry while printing. A pseudo-terminal has no rate, and a
// USB-native board ignores it: no percentage above 100 then.
std::string link_report(const Sender& sender, double baud, double scale, bool pty, double elapsed) {
  const FirmwareInfo& fw = sender.firmware();
  if (fw.baud > 0 && fw.time_scale > 0) {
    // A simulated printer says how fast it pretends to be.
    baud = fw.baud;
    scale = fw.time_scale;
  } else if (pty) {
    return "link unlimited (pseudo-terminal)";
  }
  std::string scale_note = scale != 1 ? fmt::format(", time scale {:g}", scale) : std::string();
  double capacity = elapsed * baud / 10 * scale;
  double percent = capacity > 0 ? 100.0 * static_cast<double>(sender.stats().bytes) / capacity : 0.0;
  if (percent > 100.5)
    return fmt::format("link faster than {:g} baud{} (a USB-native board ignores the rate)", baud, scale_note);
  return fmt::format("link utilisation {:.1f} % ({:g} baud{})", percent, baud, scale_note);
}

void print_summary(const Sender& sender, const PrinterLink& link, const PrintControl& control, Diagnostics& diag) {
  const double baud = link.baud();
  const double scale = link.time_scale();
  const bool pty = link.pty();
  const SenderStats& s = sender.stats();
  double elapsed = s.print_end > s.print_start && s.print_start >= 0 ? s.print_end - s.print_start : 0;
  std::string input;
  if (s.shortened > 0) input += fmt::format(", shortened {}", s.shortened);
  if (s.skipped > 0) input += fmt::format(", left out {}", s.skipped);
  if (s.unknown_commands > 0) input += fmt::format(", not taken by the firmware {}", s.unknown_commands);
  if (control.swaps() > 0) input += fmt::format(", swaps {}", control.swaps());
  if (s.resets > 0)
    input += fmt::format(", printer resets {} ({} moves, {:.1f} mm may have printed twice)", s.resets, s.redone_moves,
                         s.redone_mm);
  diag.report(fmt::format(
      "summary: lines {}, time {:.3f} s, {:.0f} lines/s, {}, flow {}, resends {}, errors {}, overdue answers {}, "
      "timeouts {}, pace probes {}, polls {}{}",
      s.lines, elapsed, elapsed > 0 ? static_cast<double>(s.lines) / elapsed : 0.0,
      link_report(sender, baud, scale, pty, elapsed), flow_mode_name(sender.flow().effective()), s.resend_requests,
      s.errors, s.probes, s.timeouts, s.pace_probes, s.polls, input));
  for (const PauseRecord& p : control.pauses()) {
    std::string latency = p.latency_mm >= 0 ? fmt::format(", motion went on {:.2f} mm and {:.3f} s (printer time) "
                                                          "after the request",
                                                          p.latency_mm, p.latency_s)
                                            : std::string();
    std::string where = p.paused_before_layer > 0 ? fmt::format("before layer {}", p.paused_before_layer)
                                                  : fmt::format("in layer {}", p.layer);
    diag.report(fmt::format("pause ({}): asked in layer {}, paused {} after input line {}{}", p.request, p.layer, where,
                            p.input_line, latency));
  }
  for (const std::string& l : control.objects().summary()) diag.report(l);
  const std::string far_end = link.summary();
  if (!far_end.empty()) diag.report(far_end);
}

// The input as the journal names it: a file by its absolute path, so that
// a resume from another folder finds it; "-" for standard input.
std::string input_name(const std::string& file) {
  if (file.empty() || file == "-") return "-";
  char* real = ::realpath(file.c_str(), nullptr);
  if (real == nullptr) return file;
  std::string out(real);
  std::free(real);
  return out;
}

void print_journal_summary(const JournalWriter& w, Diagnostics& diag) {
  diag.report(fmt::format("journal {}: {} bytes written, {} on disk, {} syncs, {} compactions", w.path(),
                          w.bytes_written(), w.file_bytes(), w.syncs(), w.compactions()));
}

int open_or_wait(const SendJob& job, double wait, Diagnostics& diag) {
  const PortOptions options{job.baud, job.reset};
  try {
    return open_serial_port(job.port, options);
  } catch (const std::runtime_error& e) {
    if (wait <= 0) throw;
    diag.warn(0, fmt::format("{}; waiting up to {:g} s for it (--reconnect)", e.what(), wait));
  }
  return wait_for_port(job.port, options, wait);
}

// The far end: the front end's choice (the simulated printer), else the device or pty at job.port.
std::unique_ptr<PrinterLink> open_link(const SendJob& job, EventLoop& loop, double wait, Diagnostics& diag) {
  if (job.link) return job.link(loop, wait, diag);
  return std::make_unique<PortLink>(job.port, PortOptions{job.baud, job.reset}, open_or_wait(job, wait, diag));
}

// A resume asks the printer what it did (printer_probe.hpp); a port that
// goes away meanwhile is waited for (--reconnect) and the printer asked
// again: it answers for what it did while the link was down.
ProbeResult probe_through_drops(PrinterLink& link, const SendJob& job, double timeout,
                                const std::function<void(std::string_view)>& trace, Diagnostics& diag) {
  for (;;) {
    try {
      return probe_printer(link.fd(), timeout, trace);
    } catch (const PortLost& e) {
      if (!link.reconnects() || job.reconnect <= 0) throw;
      diag.warn(0, fmt::format("{}; waiting up to {:g} s for {} to come back (--reconnect)", e.what(), job.reconnect,
                               job.port));
      const double lost = EventLoop::now();
      link.reopen(job.reconnect);
      diag.warn(0, fmt::format("the port is back after {:.2f} s; asking the printer again", EventLoop::now() - lost));
    }
  }
}

// The far end's motion (a simulated printer's), for the pause's latency figures.
void set_motion_probe(SendSession& session, FarMotion& m) {
  session.control()->set_probe(MotionProbe{[&m] { return m.now(); }, [&m](double t) { return m.travelled(t); },
                                           [&m](long long n) { m.watch(n); },
                                           [&m](double& end, double& queued) { return m.watched(end, queued); }});
}

// A file's layers are counted and its time estimated before it is sent (one
// quick pass), so the progress can say "layer 12/40" and give an ETA.
void count_layers(const std::string& file, SendSession& session, int e_relative) {
  InputFile again(file);
  struct stat st{};
  if (::fstat(again.fd(), &st) != 0 || !S_ISREG(st.st_mode)) return;
  Pipeline count(session.markers());
  if (e_relative >= 0) count.set_e_mode(e_relative == 1);
  LayerTimer timer(sender_estimator_options());
  count.add(timer);
  count.run(again.fd());
  session.set_total_layers(count.tracker().layer_count());
  session.set_estimated_time(timer.times().total());
}

// A journal left unfinished by a print that did not end (a killed gc-send,
// a fault) is kept beside the new one, and the command that resumes it said.
void keep_unfinished(const SendJob& job, Diagnostics& diag) {
  struct stat st{};
  if (::lstat(job.journal_path.c_str(), &st) != 0) return;
  JournalContents old;
  try {
    old = read_journal(job.journal_path);
  } catch (const JournalError&) {
    return;  // not a journal this could resume: replaced
  }
  if (old.finished || old.entries.empty()) return;
  std::string kept = job.journal_path;
  if (kept.size() > 8 && kept.ends_with(".journal")) kept.resize(kept.size() - 8);
  kept += ".unfinished.journal";
  if (::rename(job.journal_path.c_str(), kept.c_str()) != 0) return;
  diag.warn(0, fmt::format("the journal of an unfinished print ({}) is kept as {}; to go on with that print instead: {}",
                           old.header.get("input"), kept, resume_command(kept, old.header.get("input"),
                                                                          old.header.get("port"))));
}

// The log of every line both ways with timestamps (--log), and the same
// lines on stderr at -vv.
class TraceLog {
 public:
  TraceLog(const SendJob& job, Diagnostics& diag) : diag_(diag), echo_(job.verbose >= 2) {
    if (job.log_path.empty()) return;
    file_ = std::fopen(job.log_path.c_str(), "w");
    if (file_ == nullptr) throw std::runtime_error(fmt::format("cannot write {}", job.log_path));
  }
  ~TraceLog() {
    if (file_ != nullptr) std::fclose(file_);
  }
  TraceLog(const TraceLog&) = delete;
  TraceLog& operator=(const TraceLog&) = delete;

  bool wanted() const { return echo_ || file_ != nullptr; }
  void operator()(std::string_view message) const {
    if (file_ != nullptr) fmt::print(file_, "{:.6f} {}\n", EventLoop::now(), message);
    if (echo_) diag_.report(message);
  }

 private:
  Diagnostics& diag_;
  bool echo_;
  std::FILE* file_ = nullptr;
};

Sender::Logger sender_log(const TraceLog& trace, Diagnostics& diag) {
  return [&trace, &diag](LogLevel level, std::uint64_t input_line, std::string_view message) {
    if (level == LogLevel::Trace) {
      trace(message);
    } else if (level == LogLevel::Warning) {
      diag.warn(input_line, message);
    } else {
      diag.info(message);
    }
  };
}

SenderConfig sender_config(const SendJob& job, const PrinterLink& link, bool resuming) {
  SenderConfig config = job.sender;
  // A pseudo-terminal has no baud rate: its bytes cross at once, unless the
  // simulated printer behind it reports its own (M115 BAUD, TIME_SCALE).
  config.link_bytes_per_second = link.pty() ? 0 : link.baud() / 10 * link.time_scale();
  config.time_scale = link.time_scale();
  if (resuming) config.handshake = false;  // M110 N0 would lose the numbering the printer goes on with
  return config;
}

// A resume's journal carries the old one's commands up to where the print
// goes on (`carried`, send_resume.hpp).
std::unique_ptr<SendJournal> open_journal(const SendJob& job, const InputIdentity& input,
                                          std::vector<JournalEntry> carried = {}) {
  return std::make_unique<SendJournal>(JournalOptions{.path = job.journal_path}, input, job.port,
                                       std::move(carried));
}

// The sender goes on where the resume plan says: the next line exactly, or
// after a reset the resume sequence and the input from the first command
// that may not have run.
void go_on(Sender& sender, const ResumeStart& start, bool quiet, Diagnostics& diag) {
  const ResumePlan& plan = start.plan;
  if (plan.condition == PrinterCondition::KeptRunning) {
    sender.continue_from(start.next, plan.state, read_track_fields(start.point, plan.state), plan.input_line,
                         plan.layer);
    if (!quiet)
      diag.report(fmt::format("resuming: the printer kept running and took line {} last (input line {}, layer {}); "
                              "on from input line {}",
                              start.last, plan.input_line, plan.layer, plan.input_line + 1));
    return;
  }
  ResetResume way{plan.state, plan.track.top_z, plan.nozzle_z, plan.track.retracted, plan.track.retraction};
  if (plan.primed) way.prime = way.retracted;  // pushed back already: no second prime
  std::vector<std::string> sequence;
  try {
    sequence = reset_resume_lines(way, Precision());
  } catch (const std::invalid_argument& e) {
    throw ResumeError(fmt::format("cannot resume: the printer reset and cannot be brought back: {}", e.what()));
  }
  sender.continue_after_reset(start.next - 1, start.last, plan.layer, sequence, plan.state, plan.track,
                              plan.input_line);
  if (quiet) return;
  if (plan.way_back_line != 0)
    diag.report(fmt::format("resuming: the printer kept running and took line {} last, inside the way back after a "
                            "reset; that way back again, to input line {} (layer {}): heating, Z declared, X and Y "
                            "homed",
                            plan.way_back_line, plan.input_line, plan.layer));
  else
    diag.report(fmt::format("resuming: the printer reset since the print stopped ({}); going back to input line {} "
                            "(layer {}): heating, Z declared, X and Y homed, {} moves ({:.1f} mm) may print twice",
                            start.greeted ? "it greeted again" : "its line numbers are back at 0", plan.input_line,
                            plan.layer, plan.redone_moves, plan.redone_mm));
}

// gc-send was stopped after the printer took its closing M400, or while
// the print was cancelled: nothing is sent, and the journal says the print
// ended (a resume of it is then refused as finished).
SendOutcome already_complete(const SendJob& job, const ResumeSource& source, const ResumeStart& start,
                             const InputIdentity& input, Diagnostics& diag) {
  std::unique_ptr<SendJournal> journal = open_journal(job, input, carried_entries(source, start));
  journal->finish(EventLoop::now());
  if (!job.quiet)
    diag.report(fmt::format("{}; nothing sent, the journal {} is marked finished", start.complete, job.journal_path));
  return {SendEnd::AlreadyFinished, {}};
}

// The control as the journal left it: what it keeps of the verbs (the
// live speed), and the pause the print stood in.
void back_into_control(PrintControl& control, const ResumeStart& start, bool quiet, Diagnostics& diag) {
  for (const ControlVerb& verb : control_verbs())
    if (!verb.journal_field.empty()) verb.restore(control, start.point.get(verb.journal_field));
  if (start.pause_not_begun && !quiet)
    diag.report(fmt::format("the printer took none of the pause block gc-send was sending when it stopped: printing "
                            "on after input line {} (pause again if wanted)",
                            start.plan.input_line));
  if (!start.paused) return;
  std::size_t rest = control.resume_into_pause(start.paused->at, start.plan.state, start.paused->track.retracted,
                                               start.paused->track.top_z, start.paused->taken, EventLoop::now());
  if (quiet) return;
  if (rest > 0)
    diag.report(fmt::format("the last run stopped inside the pause block: its {} lines the printer had not taken go "
                            "out now",
                            rest));
  diag.report(fmt::format("the print was paused after input line {}: parked, waiting for resume",
                          start.plan.input_line));
}

// Where the session starts from besides the input: a resume's plan, or
// nothing for a fresh print.
struct SessionStart {
  const ResumeStart* resume = nullptr;
  bool from_stdin = false;  // the input is a stream: no second read of it
};

// The session's control (the park by the file's area, the E mode, the
// state a resume left), its progress, the reconnect and the layer count.
void prepare_session(SendSession& session, const SendJob& job, PrinterLink& link, const InputFile& input,
                     SessionStart from, Diagnostics& diag) {
  PrintControlConfig control = job.control;
  const bool resuming = from.resume != nullptr;
  // (A resumed stream is past its header: the park goes by the options.)
  if (job.park)
    control.park = job.park(resuming && from.from_stdin ? PrintArea{} : session.read_print_area(), control.pause);
  // A resume's E mode is the journal's state (Pipeline::start_from), and a
  // stream is past its header.
  int e_relative = resuming ? -1 : session.read_e_mode(job.e_mode, input.name());
  session.set_control(control, job.control_path);
  if (resuming) back_into_control(*session.control(), *from.resume, job.quiet, diag);
  if (link.reconnects()) session.set_reconnect(job.port, PortOptions{job.baud, false}, job.reconnect);
  ProgressOptions progress = job.progress;
  if (job.quiet) progress.mode = ProgressMode::Off;  // the status file is still kept
  session.set_progress(progress);
  if (link.motion() != nullptr) set_motion_probe(session, *link.motion());
  if (!from.from_stdin && !job.quiet && !resuming) count_layers(input.name(), session, e_relative);
  if (session.fifo() != nullptr) diag.info(fmt::format("control FIFO: {}", session.fifo()->path()));
}

// After the print: the journal closed when the print ended, the summaries,
// and how it ended; a failure says how to go on with the part on the bed.
SendOutcome finish(const Sender& sender, SendSession& session, PrinterLink& link, SendJournal* journal,
                   const SendJob& job, const std::string& input, Diagnostics& diag) {
  const SenderState state = sender.state();
  // A print the printer could not go on with ended with its safe end (heaters
  // off): nothing to resume, as after a cancel.
  const bool lost = !sender.lost().empty();
  if (journal != nullptr && (state == SenderState::Done || state == SenderState::Cancelled || lost))
    journal->finish(EventLoop::now());
  if (!job.quiet) print_summary(sender, link, *session.control(), diag);
  if (journal != nullptr && !job.quiet) print_journal_summary(journal->writer(), diag);
  // The session closed the descriptor it was given when the port went away.
  if (session.port_replaced()) link.release();
  if (state == SenderState::Done) return {SendEnd::Finished, {}};
  if (state == SenderState::Cancelled) return {SendEnd::EmergencyStop, {}};
  diag.report(sender.failure());
  if (journal != nullptr && !lost && sender.last_acknowledged().number > 0)
    diag.report(fmt::format("the journal holds the print; to go on with it: {}",
                            resume_command(journal->writer().path(), input, job.port)));
  return {SendEnd::Failed, sender.failure()};
}

SendOutcome send(SendJob& job, Diagnostics& diag) {
  // Before the journal is read or replaced: another gc-send may be writing
  // it (and printing).
  std::optional<JournalLock> lock;
  if (!job.journal_path.empty()) lock.emplace(job.journal_path);
  std::optional<ResumeSource> resume;
  if (job.resume) resume = open_resume(job.journal_path, job.file);
  const std::string file = resume ? resume->resolved : job.file;
  InputFile input(file);
  const std::string name = input_name(file);
  if (resume) check_resume_input(*resume, name, input.fd());
  if (resume && resume->not_begun()) {
    // (gc-send was stopped before its first command: a supervisor's
    // --resume after a kill in the first second needs no other case.)
    if (!job.quiet)
      diag.report(fmt::format("the journal {} holds no command: the print had not begun; beginning it",
                              job.journal_path));
    resume.reset();
  }
  EventLoop loop;
  // The journal before the port: one that cannot be kept stops the print
  // before anything reaches the printer. A resume's replaces the old one
  // once the printer has said where it is.
  std::unique_ptr<SendJournal> journal;
  if (!job.journal_path.empty() && !resume) {
    keep_unfinished(job, diag);
    journal = open_journal(job, identify_input(name, input.fd()));
  }
  const std::unique_ptr<PrinterLink> link = open_link(job, loop, resume ? job.reconnect : 0, diag);
  const SenderConfig config = sender_config(job, *link, resume.has_value());
  const TraceLog trace(job, diag);
  Sender sender(config, sender_log(trace, diag));
  sender.set_trace(trace.wanted());
  // (The session is given the port the printer answered on.)
  std::optional<ProbeResult> probe;
  if (resume) probe = probe_through_drops(*link, job, std::max(30.0, config.timeout), std::cref(trace), diag);
  SendSession session(loop, sender, input.fd(), link->fd(), diag,
                      job.layer_marker.empty() ? LayerMarkers() : LayerMarkers(job.layer_marker));
  std::optional<ResumeStart> start;
  if (resume) {
    start = begin_resume(*resume, *probe, session, ResumeLimits{.can_home_xy_alone = config.home_xy_alone});
    if (!start->complete.empty())
      return already_complete(job, *resume, *start, identify_input(name, input.fd()), diag);
    journal = open_journal(job, identify_input(name, input.fd()), carried_entries(*resume, *start));
    session.set_journal(journal.get());
    go_on(sender, *start, job.quiet, diag);
  } else if (journal) {
    session.set_journal(journal.get());
  }
  prepare_session(session, job, *link, input, SessionStart{start ? &*start : nullptr, name == "-"}, diag);
  session.run();
  return finish(sender, session, *link, journal.get(), job, name, diag);
}

}  // namespace

SendOutcome run_send_job(SendJob& job, Diagnostics& diag) {
  try {
    return send(job, diag);
  } catch (const ResumeError& e) {
    // A resume refused before anything of the print was sent.
    diag.error(e.what());
    return {SendEnd::Refused, e.what()};
  }
}

}  // namespace gcode::serial
