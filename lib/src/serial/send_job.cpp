#include "gcode/serial/send_job.hpp"

#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/core/file_io.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/report/layer_time.hpp"
#include "gcode/serial/event_loop.hpp"
#include "gcode/serial/input_identity.hpp"
#include "gcode/serial/port.hpp"
#include "gcode/serial/send_journal.hpp"
#include "gcode/serial/send_session.hpp"
#include "gcode/serial/virtual_link.hpp"

namespace gcode::serial {

namespace {

constexpr std::string_view kVirtual = "virtual";

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

void print_summary(const Sender& sender, const VirtualPrinter* printer, const PrintControl& control, double baud,
                   double scale, bool pty) {
  const SenderStats& s = sender.stats();
  double elapsed = s.print_end > s.print_start && s.print_start >= 0 ? s.print_end - s.print_start : 0;
  std::string input;
  if (s.shortened > 0) input += fmt::format(", shortened {}", s.shortened);
  if (s.skipped > 0) input += fmt::format(", left out {}", s.skipped);
  if (control.swaps() > 0) input += fmt::format(", swaps {}", control.swaps());
  fmt::print(stderr,
             "gc-send: summary: lines {}, time {:.3f} s, {:.0f} lines/s, {}, flow {}, resends {}, errors {}, "
             "overdue answers {}, timeouts {}{}\n",
             s.lines, elapsed, elapsed > 0 ? static_cast<double>(s.lines) / elapsed : 0.0,
             link_report(sender, baud, scale, pty, elapsed), flow_mode_name(sender.flow().effective()),
             s.resend_requests, s.errors, s.probes, s.timeouts, input);
  for (const PauseRecord& p : control.pauses()) {
    std::string latency = p.latency_mm >= 0 ? fmt::format(", motion went on {:.2f} mm and {:.3f} s (printer time) "
                                                          "after the request",
                                                          p.latency_mm, p.latency_s)
                                            : std::string();
    std::string where = p.paused_before_layer > 0 ? fmt::format("before layer {}", p.paused_before_layer)
                                                  : fmt::format("in layer {}", p.layer);
    fmt::print(stderr, "gc-send: pause ({}): asked in layer {}, paused {} after input line {}{}\n", p.request, p.layer,
               where, p.input_line, latency);
  }
  if (printer != nullptr) {
    const VirtualPrinterStats& v = printer->stats();
    fmt::print(stderr,
               "gc-send: virtual printer: executed {}, accepted lines {}, planner starved {:.2f} % of the print, "
               "bytes lost to overruns {}, print time {:.1f} s simulated\n",
               v.executed, v.accepted_lines, 100.0 * printer->starvation(), v.overrun_bytes,
               v.last_move_end > v.first_move ? v.last_move_end - v.first_move : 0.0);
  }
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

void print_journal_summary(const JournalWriter& w) {
  fmt::print(stderr, "gc-send: journal {}: {} bytes written, {} on disk, {} syncs, {} compactions\n", w.path(),
             w.bytes_written(), w.file_bytes(), w.syncs(), w.compactions());
}

}  // namespace

bool is_virtual_port(const std::string& port) {
  return port == kVirtual || port.rfind(std::string(kVirtual) + ":", 0) == 0;
}

int run_send_job(SendJob& job, Diagnostics& diag) {
  InputFile input(job.file);
  EventLoop loop;
  // The journal first: one that cannot be kept stops the print before
  // anything reaches the printer.
  std::unique_ptr<SendJournal> journal;
  if (!job.journal_path.empty())
    journal = std::make_unique<SendJournal>(JournalOptions{.path = job.journal_path},
                                            identify_input(input_name(job.file), input.fd()), job.port);

  // The port: a real device or pty, or a socketpair to an in-process model.
  int port_fd = -1;
  std::unique_ptr<VirtualPrinter> printer;
  std::unique_ptr<VirtualLink> link;
  std::FILE* vlog = nullptr;
  int model_fd = -1;
  double baud = job.baud;
  double scale = 1;
  bool pty = false;
  if (is_virtual_port(job.port)) {
    int fds[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
      throw std::runtime_error("cannot create the virtual printer's link");
    port_fd = fds[0];
    model_fd = fds[1];
    if (!job.vconfig.log_path.empty()) {
      vlog = std::fopen(job.vconfig.log_path.c_str(), "w");
      if (vlog == nullptr) throw std::runtime_error(fmt::format("cannot write {}", job.vconfig.log_path));
    }
    printer = std::make_unique<VirtualPrinter>(job.vconfig, vlog);
    link = std::make_unique<VirtualLink>(loop, *printer, model_fd);
    baud = job.vconfig.baud;
    scale = job.vconfig.time_scale;
  } else {
    port_fd = open_serial_port(job.port, PortOptions{job.baud, job.reset});
    pty = is_pseudo_terminal(port_fd);
  }

  SenderConfig config = job.sender;
  // A pseudo-terminal has no baud rate: its bytes cross at once, unless the
  // simulated printer behind it reports its own (M115 BAUD, TIME_SCALE).
  config.link_bytes_per_second = pty ? 0 : baud / 10 * scale;
  config.time_scale = scale;
  std::FILE* log = nullptr;
  if (!job.log_path.empty()) {
    log = std::fopen(job.log_path.c_str(), "w");
    if (log == nullptr) throw std::runtime_error(fmt::format("cannot write {}", job.log_path));
  }
  bool trace = job.verbose >= 2;
  Sender sender(config, [&](LogLevel level, std::uint64_t input_line, std::string_view message) {
    if (level == LogLevel::Trace) {
      if (log != nullptr) fmt::print(log, "{:.6f} {}\n", EventLoop::now(), message);
      if (trace) std::fprintf(stderr, "gc-send: %.*s\n", static_cast<int>(message.size()), message.data());
    } else if (level == LogLevel::Warning) {
      diag.warn(input_line, message);
    } else {
      diag.info(message);
    }
  });
  sender.set_trace(trace || log != nullptr);
  SendSession session(loop, sender, input.fd(), port_fd, diag,
                      job.layer_marker.empty() ? LayerMarkers() : LayerMarkers(job.layer_marker));
  if (journal) session.set_journal(journal.get());
  PrintControlConfig control = job.control;
  if (job.park) control.park = job.park(session.read_print_area(), control.pause);
  int e_relative = session.read_e_mode(job.e_mode, input.name());
  session.set_control(control, job.control_path);
  ProgressOptions progress = job.progress;
  if (job.quiet) progress.mode = ProgressMode::Off;  // the status file is still kept
  session.set_progress(progress);
  if (printer) {
    VirtualPrinter* p = printer.get();
    VirtualLink* l = link.get();
    session.control()->set_probe(MotionProbe{
        [l] { return l->simulated_now(); }, [p](double t) { return p->travelled(t); },
        [p](long long n) { p->watch(n); },
        [p](double& end, double& queued) {
          if (!p->watched().seen) return false;
          end = p->watched().motion_end;
          queued = p->watched().queued_length;
          return true;
        }});
  }
  if (!job.file.empty() && job.file != "-" && !job.quiet) {
    // A file's layers are counted and its time estimated before it is sent
    // (one quick pass), so the progress can say "layer 12/40" and give an
    // ETA from the estimator.
    InputFile again(job.file);
    struct stat st{};
    if (::fstat(again.fd(), &st) == 0 && S_ISREG(st.st_mode)) {
      Pipeline count(session.markers());
      if (e_relative >= 0) count.set_e_mode(e_relative == 1);
      LayerTimer timer(sender_estimator_options());
      count.add(timer);
      count.run(again.fd());
      session.set_total_layers(count.tracker().layer_count());
      session.set_estimated_time(timer.times().total());
    }
  }
  if (session.fifo() != nullptr) diag.info(fmt::format("control FIFO: {}", session.fifo()->path()));
  session.run();

  if (journal && (sender.state() == SenderState::Done || sender.state() == SenderState::Cancelled))
    journal->finish(EventLoop::now());
  if (!job.quiet) print_summary(sender, printer.get(), *session.control(), baud, scale, pty);
  if (journal && !job.quiet) print_journal_summary(journal->writer());
  if (vlog != nullptr) std::fclose(vlog);
  if (log != nullptr) std::fclose(log);
  if (model_fd >= 0) ::close(model_fd);
  ::close(port_fd);

  switch (sender.state()) {
    case SenderState::Done: return 0;
    case SenderState::Cancelled: return 130;
    default:
      std::fprintf(stderr, "gc-send: %s\n", sender.failure().c_str());
      return 1;
  }
}

}  // namespace gcode::serial
