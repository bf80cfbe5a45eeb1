#pragma once
// A model of a Marlin printer at the other end of a serial link, for tests,
// benchmarks and trying a pipeline without hardware; with another dialect
// (VirtualPrinterConfig::firmware: klipper, prusa, rrf) it answers and
// behaves as that firmware does where it differs (virtual_dialect.hpp,
// virtual_printer_flavour.cpp).
//
// It is a discrete-event simulation in simulated seconds (the caller maps
// wall time to simulated time with a time scale, see virtual_link.hpp):
//  * the link carries baud/10 bytes per second in each direction;
//  * received bytes go into an RX buffer of `rx_buffer` bytes (one slot is
//    kept free, as in Marlin's ring buffer); a byte that arrives while it is
//    full is lost, as on real hardware;
//  * between commands the firmware moves complete lines from the RX buffer
//    into a command queue of `queue` (BUFSIZE) entries, checking line number
//    and checksum with Marlin's exact messages ("Error:checksum mismatch,
//    Last Line: 41", "Resend: 42", "ok") and emptying the RX buffer after an
//    error, as Marlin does; like Marlin it reads bytes as they arrive while
//    no command blocks it and the queue has room, and keeps only the first
//    `max_line` - 1 bytes of a line (MAX_CMD_SIZE): a longer line loses its
//    checksum and is refused with "No Checksum with line number";
//  * the head of the queue executes: a move waits for a free block in a
//    planner of `planner` blocks, each taking length / feed rate; the "ok"
//    goes out when the command leaves the queue (with ADVANCED_OK fields if
//    enabled);
//  * G28, G4, M400 report "echo:busy: processing" every 2 s; M109/M190 heat
//    at a fixed rate and report temperatures every second; M105, M114, M155,
//    M110, M115 answer as Marlin does; M112 stops the printer at once;
//  * faults can be injected: corrupted lines, lost "ok"s, spurious resend
//    requests, garbage lines, busy stalls, going silent, a fatal error, a
//    disconnect; and at chosen moments (virtual_fault.hpp) a reset (queue,
//    planner, position, homing, heater targets and line numbers lost, the
//    greeting again) or a link drop, the board running on or restarting;
//  * every executed command is logged with the simulated time and position,
//    and so are resets (with the line numbers they lost: moves that had left
//    the queue but not the planner, and commands still queued) and drops, as
//    lines starting with '#': across resets and drops the log shows every
//    move the nozzle made.
//
// Its options are virtual_printer_options.hpp, the link virtual_wire.hpp,
// the texts of its answers virtual_dialect.hpp (Marlin's); each command has
// a handler of its own (process_G28, process_M109, ...).
#include <cstdint>
#include <cstdio>
#include <deque>
#include <limits>
#include <random>
#include <string>
#include <string_view>

#include "gcode/core/machine_state.hpp"
#include "gcode/serial/sim/virtual_dialect.hpp"
#include "gcode/serial/sim/virtual_flavour_state.hpp"
#include "gcode/serial/sim/virtual_printer_options.hpp"
#include "gcode/serial/sim/virtual_wire.hpp"

namespace gcode::serial {

struct VirtualPrinterStats {
  std::uint64_t executed = 0;          // commands that left the queue
  std::uint64_t accepted_lines = 0;    // numbered lines accepted
  std::uint64_t checksum_errors = 0;
  std::uint64_t line_number_errors = 0;
  std::uint64_t overrun_bytes = 0;     // bytes lost to a full RX buffer
  std::uint64_t held_writes = 0;       // writes that waited for room (write_timeout)
  std::uint64_t timed_out_bytes = 0;   // ... bytes of them dropped when the wait timed out (in overrun_bytes too)
  std::uint64_t scripted_errors = 0;   // OctoPrint's scripted refusals fired
  std::uint64_t drained_bytes = 0;     // bytes thrown away after an error
  std::uint64_t corrupted = 0, dropped_oks = 0, spurious_resends = 0, garbage_lines = 0, busy_stalls = 0;
  std::uint64_t rx_bytes = 0, tx_bytes = 0;
  std::uint64_t moves = 0;
  std::uint64_t resets = 0, link_drops = 0;
  double first_move = -1;              // when the first block started
  double last_move_end = -1;           // when the last block ended
  double starved = 0;                  // planner empty while waiting for the next move
};

class VirtualPrinter {
 public:
  explicit VirtualPrinter(const VirtualPrinterConfig& config, std::FILE* log = nullptr);

  // Bytes written by the host at simulated time `now`: they reach the RX
  // buffer one byte time apart, after what is already on the wire.
  // While the link is down they are lost.
  void receive(std::string_view bytes, double now) {
    if (!outage_.down()) wire_.receive(bytes, now);
  }
  // Runs the model up to `now`.
  void advance(double now);
  // When the model next has something to do (an arriving byte, a finished
  // move, a message to send); infinity when idle.
  double next_event() const;
  // Bytes whose transmission to the host has completed by `now`; the caller
  // takes them with `take(n)`.
  std::string_view transmitted(double now) const { return wire_.transmitted(now); }
  void take(std::size_t n) { wire_.take(n); }
  // Writes out the log lines the model has buffered (one write for all the
  // commands that ended since the last call, not one each).
  void flush_log() {
    if (log_ != nullptr) std::fflush(log_);
  }

  bool disconnected() const { return disconnected_; }
  // The board restarts at `t` (after advance(t)): what it had queued and
  // planned is lost, it greets again.
  void reset(double t);
  // The link goes down at `t` for `seconds`: bytes on the way are lost, the
  // board executes what it has; with `reset_after` it restarts when the link
  // comes back.
  void drop_link(double t, double seconds, bool reset_after);
  bool link_down() const { return outage_.down(); }
  // Homed since the last reset (G28).
  bool homed() const { return homed_; }
  // Layers begun: new heights at which the printer extruded (kept across resets).
  int layer() const { return layer_; }
  // Halted (Marlin's kill(): silent from then on) or shut down (Klipper:
  // every command refused until FIRMWARE_RESTART).
  bool halted() const { return halted_ || flavour_.shut_down(); }
  const VirtualPrinterStats& stats() const { return stats_; }
  const VirtualPrinterConfig& config() const { return config_; }
  // The time the planner was empty between moves, as a fraction of the time
  // from the first move to the last.
  double starvation() const;

  // Exact figures for a pause (gc-send's latency report): the nozzle's path
  // length (XYZ) travelled by simulated time `t` (not before the last
  // event), and, for the command numbered `number`, when the motion ahead of
  // it ended and how long a path had been queued before it started.
  double travelled(double t) const;
  struct Watch {
    long long number = -1;
    bool seen = false;
    double motion_end = 0;
    double queued_length = 0;
  };
  void watch(long long number) { watch_ = Watch{number, false, 0, 0}; }
  const Watch& watched() const { return watch_; }

 private:
  enum class Wait : std::uint8_t { None, PlannerSlot, PlannerEmpty, Dwell, Heating, Homing, Stall, User };
  // What follows a wait for the planner to empty.
  enum class After : std::uint8_t { Nothing, Home, Dwell, User, OwnPause };
  struct Command {
    std::string text;      // without N and checksum
    long long number = -1;
  };

  void arrive(char c, double t);
  void run(double t);
  void parse_rx();
  void admit_held();
  double held_deadline() const;
  bool scripted_error(long long n);
  bool process_line(std::string& line);
  void queue_unchecked(std::string_view line);
  void push_command(std::string_view text, long long number);
  void reject(LineFault fault);
  void start(double t);
  bool execute(const Line& line, const Move& m, double t);
  bool process_unknown(const Line& line);
  bool process_move(const Move& m, double t);
  bool process_G4(const Line& line, double t);
  bool process_G28(double t);
  bool process_M104(const Line& line);
  bool process_M105();
  bool process_M109(const Line& line, double t);
  bool process_M110(const Line& line);
  bool process_M112();
  bool process_M114();
  bool process_M115();
  bool process_M155(const Line& line, double t);
  bool process_M400(double t);
  bool wait_for_planner(double t, After after, double duration);
  bool planner_full(double t) const;
  int planner_capacity() const;
  double idle_wait_at() const;
  // The firmware's own ways (virtual_printer_flavour.cpp).
  bool refused(const Line& line);
  void drop_head();
  bool moves_axes(const Line& line) const;
  void halt(std::string_view why);
  void fail_homing();
  bool process_extended(const Line& line);
  bool process_M600(double t);
  bool process_M601(double t);
  bool process_M115_version(const Line& line, double t);
  bool end_user_wait();
  void set_target(const Line& line);
  bool still_waiting(double t);
  void finish(double t);
  void add_block(double duration, double t);
  void planner_step(double t);
  void send(std::string_view text);
  void send_ok(long long number);
  void update_temperatures(double t);
  Temperatures temperatures() const;
  bool heated() const;
  double heat_done_time() const;
  bool chance(double p);
  void fire(const ScheduledFault& fault, double t);
  void link_up(double t);
  void note(const std::string& text);

  VirtualPrinterConfig config_;
  std::FILE* log_;
  const ReplyDialect* dialect_ = &marlin_dialect();
  double now_ = 0;               // the time of the event being processed

  VirtualWire wire_;
  std::string last_sent_;       // the line sent last (a reset may cut it: GreetingForm::CutLine)
  std::string rx_;              // the RX ring buffer (front = oldest)
  std::size_t rx_head_ = 0;
  std::string partial_;         // the line being read out of the RX buffer
  std::string emergency_;       // the start of the line arriving, for the emergency parser
  std::string held_;            // bytes of a write waiting for room in the RX buffer (write_timeout)
  double held_since_ = 0;
  int scripted_fired_ = 0;      // scripted errors fired (scripted_errors)

  std::deque<Command> queue_;
  std::deque<Command> spare_;   // reused strings
  Wait wait_ = Wait::None;
  double wait_until_ = 0;
  double next_busy_ = 0;
  double next_report_ = 1e300;  // heating report or M155 autoreport
  double next_idle_wait_ = 0;   // the next "wait" while idle (idle_wait)
  double autoreport_ = 0;       // M155 interval, 0 = off
  bool heating_bed_ = false;
  double pending_duration_ = 0; // of a move waiting for a planner block
  After after_ = After::Nothing;
  double after_duration_ = 0;
  bool ok_sent_ = false;        // M105 answers on its ok line

  std::deque<double> planner_;  // durations; the front one runs
  std::deque<double> lengths_;  // their path lengths
  std::deque<long long> block_numbers_;  // their commands' line numbers
  double pending_length_ = 0;   // of a move waiting for a planner block
  bool pending_block_ = true;   // the move waiting takes a block (one that moves nothing takes none)
  double done_length_ = 0;      // path of the blocks finished
  double queued_length_ = 0;    // path of every block added
  Watch watch_;
  double head_end_ = 0;
  double empty_since_ = -1;
  bool waited_while_empty_ = false;

  MachineState state_;
  long long last_n_ = 0;
  double hotend_ = 20, bed_ = 20, hotend_target_ = 0, bed_target_ = 0, temp_time_ = 0;
  bool halted_ = false, silent_ = false, disconnected_ = false;
  FlavourState flavour_;         // Klipper's shutdown, Prusa's own pause (virtual_printer_flavour.cpp)
  FaultSchedule schedule_;
  LinkOutage outage_;
  bool homed_ = false;
  bool homing_fails_ = false;  // the G28 under way ends without its endstop (home-fails)
  int layer_ = 0, started_layer_ = 0;  // started_layer_: by the command executing
  double top_z_ = -1e300;
  std::mt19937 rng_;
  VirtualPrinterStats stats_;
};

}  // namespace gcode::serial
