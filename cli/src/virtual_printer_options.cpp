#include "gcode/cli/virtual_printer_options.hpp"

#include <CLI/CLI.hpp>

#include "gcode/core/firmware.hpp"

namespace gcode::cli {

namespace {

void add_firmware_options(CLI::App& app, VirtualPrinterToolOptions& o) {
  serial::VirtualPrinterConfig& c = o.config;
  app.add_option("--firmware", c.firmware,
                 "Whose replies and ways (default " + c.firmware + "): " + firmware_names() +
                     "; FIRMWARE FLAVOURS in the man page says how each differs")
      ->type_name("NAME");
  app.add_option("--user-seconds", c.user_seconds,
                 "How long the user at the printer takes to answer a wait for them (Prusa's M600, its own pause), "
                 "in simulated seconds (default 5)")
      ->type_name("S");
  app.add_option("--baud", c.baud, "Simulated link speed (default 250000)")->type_name("BAUD");
  app.add_option("--queue", c.queue, "Command queue entries, Marlin BUFSIZE (default 4)")->type_name("N");
  app.add_option("--rx-buffer", c.rx_buffer, "Serial receive buffer, RX_BUFFER_SIZE (default 128)")->type_name("BYTES");
  app.add_option("--write-timeout", c.write_timeout,
                 "A write that meets a full receive buffer waits for room up to S simulated seconds, then the rest "
                 "of it is dropped (default 0: lost at once)")
      ->type_name("S");
  app.add_flag("--scripted-errors", c.scripted_errors,
               "OctoPrint's scripted errors: lines 100, 105 (its ok lost), 110 (no line number) and 115 refused once");
  app.add_flag("--octoprint", o.octoprint,
               "OctoPrint's virtual printer's defaults: --rx-buffer 64 --write-timeout 10 --scripted-errors "
               "--instant-moves");
  app.add_option("--max-line", c.max_line,
                 "Command buffer, MAX_CMD_SIZE (default 96): a line keeps its first BYTES - 1 bytes")
      ->type_name("BYTES");
  app.add_option("--planner", c.planner, "Planner blocks, BLOCK_BUFFER_SIZE (default 16; like Marlin, they hold one move fewer)")->type_name("N");
  app.add_option("--time-scale", c.time_scale, "Run this many times faster than real time (default 1)")
      ->type_name("X");
  app.add_option("--speed-factor", c.speed_factor,
                 "Moves run X times faster than their feed rates, untold to the host (default 1)")
      ->type_name("X");
  app.add_flag("--advanced-ok", c.advanced_ok, "Answer \"ok N<n> P<planner free> B<queue free>\"");
  app.add_flag("--instant-moves", c.instant_moves, "Moves take no time: only the link limits the speed");
  app.add_flag("--no-resend-ok", o.no_resend_ok, "No ok after \"Resend: n\" (Marlin sends one; some firmwares none)");
  app.add_option("--idle-wait", c.idle_wait,
                 "Say \"wait\" every S simulated seconds while idle, as Marlin with NO_TIMEOUTS (default 0: never)")
      ->type_name("S");
  app.add_flag("--no-link-report", o.no_link_report,
               "M115 does not name the simulated BAUD and TIME_SCALE, as a real firmware behind a pty");
  app.add_option("--heat-rate", c.heat_rate, "Heating in degrees per second (default 10; the bed a third of it)")
      ->type_name("DEG_PER_S");
}

void add_fault_options(CLI::App& app, VirtualPrinterToolOptions& o) {
  app.add_option("--fault", o.faults,
                 "Inject a fault, repeatable: corrupt=P drop-ok=P resend=P garbage=P busy=P (P per line), "
                 "silent-after=N halt-after=N disconnect-after=N (N commands), seed=S; at a chosen moment: "
                 "reset@WHEN (the board restarts), drop=S@WHEN (the link is gone S simulated seconds, the board "
                 "runs on), drop-reset=S@WHEN (and restarts when it returns), WHEN being line=N (after command "
                 "N, or the first numbered past it), time=S (simulated second S) or layer=N (after the first extruding move of layer N)")
      ->type_name("KEY=VALUE");
  app.add_option("--greeting", o.greeting,
                 "How the board greets after a reset: start, nul (a NUL before start), twice (start twice), "
                 "external (start, echo: External Reset, the firmware line), cut (start right after the first half of "
                 "the line it was sending); default start")
      ->type_name("FORM");
  app.add_option("--drop-seconds", o.run.drop_seconds,
                 "How long a link drop fired by SIGUSR2 lasts, in simulated seconds (default 5); SIGUSR1 "
                 "resets the board")
      ->type_name("S");
}

void resolve(VirtualPrinterToolOptions& o) {
  serial::VirtualPrinterConfig& c = o.config;
  std::string opts;
  for (const std::string& f : o.faults) opts += f + ",";
  serial::parse_virtual_options(opts + "firmware=" + c.firmware, c);
  c.greeting = serial::parse_greeting_form(o.greeting);
  if (o.no_link_report) c.report_link = false;
  if (o.octoprint) gcode::serial::parse_virtual_options("octoprint", c);
  if (o.no_resend_ok) c.resend_ok = false;
  if (c.baud < 50 || c.queue < 1 || c.rx_buffer < 16 || c.max_line < 16 || c.planner < 1 || !(c.time_scale > 0) ||
      !(c.speed_factor > 0) || !(o.run.drop_seconds >= 0) || !(c.user_seconds >= 0) || !(c.idle_wait >= 0))
    throw UsageError(
        "--baud, --queue, --rx-buffer, --max-line, --planner, --time-scale, --speed-factor, --drop-seconds and "
        "--user-seconds need sensible values");
}

}  // namespace

void add_virtual_printer_options(Tool& tool, VirtualPrinterToolOptions& o) {
  CLI::App& app = tool.app();
  app.add_option("--link", o.run.link, "Path of the symlink to create for the pseudo-terminal")
      ->type_name("PATH")
      ->required();
  add_firmware_options(app, o);
  add_fault_options(app, o);
  app.add_option("--log", o.run.log, "Write every executed command: time, N, X, Y, Z, E, command (tab-separated)")
      ->type_name("FILE");
  app.add_flag("-q,--quiet", o.run.quiet, "No messages on standard error");
  tool.check([&o] { resolve(o); });
}

}  // namespace gcode::cli
