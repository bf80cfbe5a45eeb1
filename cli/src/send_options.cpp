#include "gcode/cli/send_options.hpp"

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <charconv>
#include <memory>

#include "gcode/serial/control/control_fifo.hpp"
#include "gcode/serial/control/object_cancel.hpp"
#include "gcode/serial/journal/journal.hpp"
#include "gcode/serial/protocol/line_check.hpp"
#include "gcode/serial/sim/virtual_printer_link.hpp"
#include "gcode/transform/custom_gcode.hpp"

namespace gcode::cli {

void add_send_options(Tool& tool, SendOptions& o) {
  CLI::App& app = tool.app();
  serial::SendJob& j = o.job;
  // -q and -v are gc-send's own below: they also govern the progress.
  tool.add_filter_options(o.io, kInput | kLayerMarker | kEMode);
  const char* link = "Link";
  app.add_option("-p,--port", j.port, "Serial port or pseudo-terminal path, or virtual[:key=value,...] (default: virtual)")
      ->type_name("PATH|virtual[:OPTS]")->group(link);
  app.add_option("-b,--baud", j.baud, "Baud rate, any value (default 250000; 115200, 500000 ...)")->type_name("BAUD")->group(link);
  app.add_option("--flow", o.flow, "auto (default), window, ping-pong or advanced-ok")
      ->type_name("MODE")->check(CLI::IsMember({"window", "ping-pong", "advanced-ok", "auto"}))->group(link);
  app.add_option("--queue", o.queue, "Commands the firmware queues (Marlin BUFSIZE, default 4)")->type_name("N")->group(link);
  app.add_option("--rx-buffer", o.rx_buffer, "Firmware serial receive buffer in bytes (RX_BUFFER_SIZE, default 128)")
      ->type_name("BYTES")->group(link);
  app.add_flag("--no-pace", o.no_pace,
               "Let the flow control alone decide what is in flight (default: no more moves in flight than keep the "
               "printer busy, so a pause stops after what its planner holds; on Marlin without ADVANCED_OK a bare G1, "
               "which moves nothing, asks when the planner has room)")->group(link);
  app.add_option("--timeout", o.timeout,
                 "Seconds without any sign of life before asking with M105 (default 10; longer for heating and "
                 "homing); an answer overdue by the printer's own pace is asked for at once")
      ->type_name("SECONDS")->group(link);
  app.add_option("--max-timeouts", o.max_timeouts, "Silent rounds in a row before giving up (default 5)")
      ->type_name("N")->group(link);
  app.add_option("--max-line", o.max_line,
                 "Longest line the firmware takes, N and checksum included (Marlin MAX_CMD_SIZE; default 96, or "
                 "what M115 reports): longer M117/M118 text is shortened, other longer lines stop the print")
      ->type_name("BYTES")->group(link);
  app.add_flag("--skip-bad-lines", j.sender.skip_bad_lines,
               "Leave out lines the firmware cannot take (over-long, control bytes, binary junk) and go on, "
               "instead of stopping before the first")->group(link);
  app.add_flag("--reset,!--no-reset", j.reset, "Pulse DTR to restart the board on connect (default: no)")->group(link);
  app.add_option("--reconnect", j.reconnect,
                 "When the port fails mid-print (EIO, ENODEV, a hang-up), wait up to SECONDS for it to come back at "
                 "the same path, open it again without a DTR reset and go on where the printer is; with --resume also "
                 "a port that is away when gc-send starts or while it asks the printer (default 180; 0: stop at once)")
      ->type_name("SECONDS")->check(CLI::NonNegativeNumber)->group(link);
  app.add_flag("--delta", o.delta,
               "The printer is a delta (its towers home together, Z with them): a printer reset mid-print is not "
               "resumed (the part is on the bed); gc-send stops and says how gc-relayer --resume-from-z finishes the "
               "part")->group(link);
  app.add_flag("--list-ports", o.list_ports, "List candidate serial ports and exit")->group(link);

  const char* control = "Control";
  app.add_option("--control", o.control,
                 "Control FIFO (default $XDG_RUNTIME_DIR/gc-send/PORT.fifo, else /tmp/gc-send-UID/PORT.fifo); made "
                 "0600, refused if not a FIFO, another user's, or writable by others")
      ->type_name("PATH")->group(control);
  app.add_flag("--no-control", o.no_control, "No control FIFO")->group(control)->excludes("--control");
  app.add_option("--journal", o.journal,
                 "Journal of what was sent, for a resume after a fault (default $XDG_STATE_HOME/gc-send/PORT.journal, "
                 "else ~/.local/state/gc-send/PORT.journal; none for the built-in virtual printer, which ends with "
                 "gc-send); made 0600, refused in a folder others can write")
      ->type_name("PATH")->group(control);
  app.add_flag("--no-journal", o.no_journal, "Keep no journal")->group(control)->excludes("--journal");
  app.add_option("--resume", o.resume,
                 "Go on with the print a journal holds (default: the port's journal; a path ending in .journal) "
                 "after gc-send was killed or crashed: checks that FILE (default: the journal's) is the same input, "
                 "asks the printer which line it took last and where it stands, and goes on from the next line")
      ->type_name("[JOURNAL]")->expected(0, 1)->group(control);
  app.add_option("--rush", j.control.rush, "After a pause request, the rest of the layer runs this many times faster")
      ->type_name("FACTOR")->capture_default_str()->check(CLI::Range(1.0, 10.0))->group(control);
  app.add_option("--max-speed", j.control.max_speed, "Cap on rushed moves, mm/s (default: none)")
      ->type_name("MM/S")->check(positive())->group(control);
  app.add_option("--max-flow", j.control.max_flow, "Cap on rushed moves' flow, mm^3/s (default: none)")
      ->type_name("MM3/S")->check(positive())->group(control);
  app.add_option("--filament-diameter", j.control.filament_diameter, "For --max-flow, mm")
      ->type_name("MM")->capture_default_str()->check(positive())->group(control);
  app.add_option("--pause-on", o.pause_on,
                 "M-codes handled as a host pause and not sent, e.g. M0,M1,M25,M601 (@pause and ;@pause always are)")
      ->type_name("CODES")->group(control);
  app.add_option("--exclude", o.exclude,
                 "Objects left out of the print, by id or name (gc-objects lists them), host side on every firmware; "
                 "`cancel object` leaves out more while it prints")
      ->type_name("ID[,ID...]")->group(control);
  app.add_option("--cancel-gcode", o.cancel_gcode,
                 "G-code (a file, or text with \\n between lines) after the park of a cancel (default: "
                 "M104 S0, M140 S0, M107, M84)")
      ->type_name("GCODE")->group(control);

  const char* progress = "Progress";
  app.add_flag("-q,--quiet", j.quiet, "Only errors on standard error (no progress, no summary)")->group(progress);
  app.add_flag("-v,--verbose", j.verbose,
               "Also report resends, printer messages and host commands; twice: every line both ways")->group(progress);
  app.add_option("--progress-interval", o.interval, "Seconds between progress lines when stderr is no terminal")
      ->type_name("SECONDS")->capture_default_str()->check(positive())->group(progress);
  app.add_option("--status-file", j.progress.status_file, "Keep the progress as JSON in this file (atomic rewrites)")
      ->type_name("PATH")->group(progress);
  app.add_option("--log", j.log_path, "Write every line sent and received, with timestamps, to this file")
      ->type_name("FILE")->group(progress);
  add_pause_options(tool, o.pause, false);
}

// --resume [JOURNAL] [FILE]: the one value after --resume is the journal
// when it ends in .journal, else the file.
void resolve_resume(const CLI::App& app, SendOptions& o) {
  serial::SendJob& j = o.job;
  j.resume = app.count("--resume") > 0;
  if (!j.resume) return;
  if (serial::is_virtual_port(j.port))
    throw UsageError("--resume needs the port of the printer that went on printing (a device, or gc-virtual-printer's "
                     "pty): the built-in virtual printer ended with the gc-send that ran it");
  if (o.no_journal) throw UsageError("--resume reads a journal: not with --no-journal");
  std::string value = o.resume;
  if (!value.empty() && !value.ends_with(".journal")) {
    if (!j.file.empty()) throw UsageError("--resume: '" + value + "' is not a journal (its name ends in .journal)");
    j.file = value;
    value.clear();
  }
  if (!value.empty()) {
    if (!o.journal.empty() && o.journal != value) throw UsageError("--resume JOURNAL and --journal name two journals");
    j.journal_path = value;
  }
}

void resolve_send_options(Tool& tool, SendOptions& o) {
  CLI::App& app = tool.app();
  serial::SendJob& j = o.job;
  if (j.baud <= 0) throw UsageError("--baud must be above 0");
  if (o.queue < 1) throw UsageError("--queue must be at least 1");
  if (o.rx_buffer < 16) throw UsageError("--rx-buffer must be at least 16");
  if (!(o.timeout > 0)) throw UsageError("--timeout must be above 0");
  if (o.max_timeouts < 0) throw UsageError("--max-timeouts must be 0 or more");
  if (o.max_line < 16) throw UsageError("--max-line must be at least 16");
  j.file = o.io.file;
  j.layer_marker = o.io.layer_marker;
  parse_e_mode(o.io.e_mode, j.e_mode);  // checked by the option already
  serial::SenderConfig& s = j.sender;
  s.flow = *serial::parse_flow_mode(o.flow);
  s.queue = o.queue;
  s.rx_buffer = o.rx_buffer;
  s.timeout = o.timeout;
  s.max_timeouts = o.max_timeouts;
  s.home_xy_alone = !o.delta;
  s.max_line = static_cast<std::size_t>(o.max_line);
  s.max_line_from_firmware = app.count("--max-line") == 0;
  s.pace = !o.no_pace;
  s.read_ahead = 1;
  if (serial::is_virtual_port(j.port) && j.port.size() > 7)
    serial::parse_virtual_options(std::string_view(j.port).substr(8), o.vconfig);
  if (serial::is_virtual_port(j.port) && app.count("--baud") > 0 && j.port.find("baud=") == std::string::npos)
    o.vconfig.baud = j.baud;
  // The far end: the simulated printer for virtual[:OPTIONS], else the job opens the port.
  if (serial::is_virtual_port(j.port))
    j.link = [config = o.vconfig](serial::EventLoop& loop, double, Diagnostics&) {
      return std::make_unique<serial::VirtualPrinterLink>(loop, config);
    };
  std::string_view codes = o.pause_on;
  while (!codes.empty()) {
    std::size_t comma = codes.find(',');
    std::string_view one = codes.substr(0, comma);
    int n = -1;
    if (one.size() < 2 || (one[0] != 'M' && one[0] != 'm') ||
        std::from_chars(one.data() + 1, one.data() + one.size(), n).ptr != one.data() + one.size())
      throw UsageError("--pause-on: '" + std::string(one) + "' is not an M-code (e.g. M0,M1,M25,M601)");
    j.control.pause_on.push_back(n);
    codes = comma == std::string_view::npos ? std::string_view() : codes.substr(comma + 1);
  }
  j.control.exclude = serial::object_terms(o.exclude);
  resolve_pause_options(o.pause);
  j.control.pause = o.pause.config;
  j.control_path = o.no_control ? std::string() : !o.control.empty() ? o.control : serial::default_control_path(j.port);
  // The built-in virtual printer ends with the gc-send that runs it: nothing
  // could resume from its journal, and concurrent virtual prints would share one.
  const bool keeps_journal = !o.no_journal && (!o.journal.empty() || !serial::is_virtual_port(j.port));
  j.journal_path = !keeps_journal ? std::string() : !o.journal.empty() ? o.journal : serial::default_journal_path(j.port);
  resolve_resume(app, o);
  j.progress.mode = isatty(STDERR_FILENO) ? serial::ProgressMode::Live : serial::ProgressMode::Plain;
  j.progress.interval = o.interval;
  PauseOptions* pause = &o.pause;
  j.park = [pause](const PrintArea& area, PauseConfig& config) { return park_rules(*pause, area, config); };
}

}  // namespace gcode::cli
