// gc-send: stream G-code to a printer over a serial port (or to the built-in
// virtual printer), keeping the printer's buffers full without overrunning
// them.
#include <sys/socket.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "gcode/core/diagnostics.hpp"
#include "gcode/serial/event_loop.hpp"
#include "gcode/serial/port.hpp"
#include "gcode/serial/send_session.hpp"
#include "gcode/serial/sender.hpp"
#include "gcode/serial/virtual_link.hpp"
#include "gcode/serial/virtual_printer.hpp"
#include "gcode/cli/io.hpp"
#include "gcode/cli/tool.hpp"

namespace {

using namespace gcode::serial;

struct Options {
  std::string file;
  std::string port = "virtual";
  int baud = 250000;
  std::string flow = "window";
  int queue = 4;
  int rx_buffer = 128;
  double timeout = 10;
  int max_timeouts = 5;
  int max_line = static_cast<int>(kDefaultMaxLine);
  bool max_line_given = false;
  bool skip_bad_lines = false;
  bool reset = false;
  bool list_ports = false;
  bool quiet = false;
  int verbose = 0;
};

constexpr std::string_view kVirtual = "virtual";

bool is_virtual(const std::string& port) {
  return port == kVirtual || port.rfind(std::string(kVirtual) + ":", 0) == 0;
}

int list_ports() {
  auto ports = list_serial_ports();
  for (const PortInfo& p : ports) std::printf("%s\t%s\n", p.path.c_str(), p.description.c_str());
  if (ports.empty()) std::fprintf(stderr, "gc-send: no serial ports found (--port virtual needs none)\n");
  return 0;
}

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

void print_summary(const Sender& sender, const VirtualPrinter* printer, double baud, double scale, bool pty) {
  const SenderStats& s = sender.stats();
  double elapsed = s.print_end > s.print_start && s.print_start >= 0 ? s.print_end - s.print_start : 0;
  std::string input;
  if (s.shortened > 0) input += fmt::format(", shortened {}", s.shortened);
  if (s.skipped > 0) input += fmt::format(", left out {}", s.skipped);
  fmt::print(stderr,
             "gc-send: summary: lines {}, time {:.3f} s, {:.0f} lines/s, {}, flow {}, resends {}, errors {}, "
             "overdue answers {}, timeouts {}{}\n",
             s.lines, elapsed, elapsed > 0 ? static_cast<double>(s.lines) / elapsed : 0.0,
             link_report(sender, baud, scale, pty, elapsed), flow_mode_name(sender.flow().effective()),
             s.resend_requests, s.errors, s.probes, s.timeouts, input);
  if (printer != nullptr) {
    const VirtualPrinterStats& v = printer->stats();
    fmt::print(stderr,
               "gc-send: virtual printer: executed {}, accepted lines {}, planner starved {:.2f} % of the print, "
               "bytes lost to overruns {}, print time {:.1f} s simulated\n",
               v.executed, v.accepted_lines, 100.0 * printer->starvation(), v.overrun_bytes,
               v.last_move_end > v.first_move ? v.last_move_end - v.first_move : 0.0);
  }
}

int run(const Options& o, const VirtualPrinterConfig& vconfig) {
  gcode::Diagnostics diag("gc-send", o.quiet ? -1 : o.verbose);
  gcode::InputFile input(o.file);
  EventLoop loop;

  // The port: a real device or pty, or a socketpair to an in-process model.
  int port_fd = -1;
  std::unique_ptr<VirtualPrinter> printer;
  std::unique_ptr<VirtualLink> link;
  std::FILE* vlog = nullptr;
  int model_fd = -1;
  double baud = o.baud;
  double scale = 1;
  bool pty = false;
  if (is_virtual(o.port)) {
    int fds[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
      throw std::runtime_error("cannot create the virtual printer's link");
    port_fd = fds[0];
    model_fd = fds[1];
    if (!vconfig.log_path.empty()) {
      vlog = std::fopen(vconfig.log_path.c_str(), "w");
      if (vlog == nullptr) throw std::runtime_error(fmt::format("cannot write {}", vconfig.log_path));
    }
    printer = std::make_unique<VirtualPrinter>(vconfig, vlog);
    link = std::make_unique<VirtualLink>(loop, *printer, model_fd);
    baud = vconfig.baud;
    scale = vconfig.time_scale;
  } else {
    port_fd = open_serial_port(o.port, PortOptions{o.baud, o.reset});
    pty = is_pseudo_terminal(port_fd);
  }

  SenderConfig config;
  config.flow = *parse_flow_mode(o.flow);
  config.queue = o.queue;
  config.rx_buffer = o.rx_buffer;
  config.timeout = o.timeout;
  config.max_timeouts = o.max_timeouts;
  // A pseudo-terminal has no baud rate: its bytes cross at once, unless the
  // simulated printer behind it reports its own (M115 BAUD, TIME_SCALE).
  config.link_bytes_per_second = pty ? 0 : baud / 10 * scale;
  config.time_scale = scale;
  config.max_line = static_cast<std::size_t>(o.max_line);
  config.max_line_from_firmware = !o.max_line_given;
  config.skip_bad_lines = o.skip_bad_lines;
  Sender sender(config, [&diag](LogLevel level, std::uint64_t input_line, std::string_view message) {
    if (level == LogLevel::Trace) {
      std::fprintf(stderr, "gc-send: %.*s\n", static_cast<int>(message.size()), message.data());
    } else if (level == LogLevel::Warning) {
      diag.warn(input_line, message);
    } else {
      diag.info(message);
    }
  });
  sender.set_trace(o.verbose >= 2);
  SendSession session(loop, sender, input.fd(), port_fd, diag);
  session.run();

  if (!o.quiet) print_summary(sender, printer.get(), baud, scale, pty);
  if (vlog != nullptr) std::fclose(vlog);
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

}  // namespace

int main(int argc, char** argv) {
  Options o;
  gcode::cli::Tool tool(
      "gc-send",
      "gc-send: stream G-code to a printer over a serial port, keeping its buffers full without overrunning\n"
      "them. Comments, blank lines and host commands (@pause) are not sent; every line is numbered and\n"
      "checksummed, resent on request, and the end waits for M400. Ctrl-C stops sending; Ctrl-C twice sends\n"
      "M112. The default port is the built-in virtual printer:\n"
      "  gc-subdivide --max 0.2 part.gcode | gc-send --port /dev/ttyACM0 --baud 250000\n"
      "  gc-send --port virtual:time-scale=20 examples/cube.gcode");
  CLI::App& app = tool.app();
  app.add_option("FILE", o.file, "G-code file; - or absent: standard input");
  app.add_option("-p,--port", o.port,
                 "Serial port or pseudo-terminal path, or virtual[:key=value,...] (default: virtual)")
      ->type_name("PATH|virtual[:OPTS]");
  app.add_option("-b,--baud", o.baud, "Baud rate, any value (default 250000; 115200, 500000 ...)")->type_name("BAUD");
  app.add_option("--flow", o.flow, "window (default), ping-pong, advanced-ok or auto")
      ->type_name("MODE")
      ->check(CLI::IsMember({"window", "ping-pong", "advanced-ok", "auto"}));
  app.add_option("--queue", o.queue, "Commands the firmware queues (Marlin BUFSIZE, default 4)")->type_name("N");
  app.add_option("--rx-buffer", o.rx_buffer, "Firmware serial receive buffer in bytes (RX_BUFFER_SIZE, default 128)")
      ->type_name("BYTES");
  app.add_option("--timeout", o.timeout,
                 "Seconds without any sign of life before asking with M105 (default 10; longer for heating and "
                 "homing); an answer overdue by the printer's own pace is asked for at once")
      ->type_name("SECONDS");
  app.add_option("--max-timeouts", o.max_timeouts, "Silent rounds in a row before giving up (default 5)")
      ->type_name("N");
  app.add_option("--max-line", o.max_line,
                 "Longest line the firmware takes, N and checksum included (Marlin MAX_CMD_SIZE; default 96, or "
                 "what M115 reports): longer M117/M118 text is shortened, other longer lines stop the print")
      ->type_name("BYTES");
  app.add_flag("--skip-bad-lines", o.skip_bad_lines,
               "Leave out lines the firmware cannot take (over-long, control bytes, binary junk) and go on, "
               "instead of stopping before the first");
  app.add_flag("--reset,!--no-reset", o.reset, "Pulse DTR to restart the board on connect (default: no)");
  app.add_flag("--list-ports", o.list_ports, "List candidate serial ports and exit");
  app.add_flag("-q,--quiet", o.quiet, "Only errors on standard error (no summary)");
  app.add_flag("-v,--verbose", o.verbose, "Also report resends, printer messages and host commands; twice: every line both ways");
  VirtualPrinterConfig vconfig;
  tool.check([&] {
    using gcode::cli::UsageError;
    if (o.baud <= 0) throw UsageError("--baud must be above 0");
    if (o.queue < 1) throw UsageError("--queue must be at least 1");
    if (o.rx_buffer < 16) throw UsageError("--rx-buffer must be at least 16");
    if (!(o.timeout > 0)) throw UsageError("--timeout must be above 0");
    if (o.max_timeouts < 0) throw UsageError("--max-timeouts must be 0 or more");
    if (o.max_line < 16) throw UsageError("--max-line must be at least 16");
    o.max_line_given = app.count("--max-line") > 0;
    if (is_virtual(o.port) && o.port.size() > kVirtual.size())
      parse_virtual_options(std::string_view(o.port).substr(kVirtual.size() + 1), vconfig);
    if (is_virtual(o.port) && app.count("--baud") > 0 && o.port.find("baud=") == std::string::npos)
      vconfig.baud = o.baud;
  });
  return tool.run(argc, argv, [&] { return o.list_ports ? list_ports() : run(o, vconfig); });
}
