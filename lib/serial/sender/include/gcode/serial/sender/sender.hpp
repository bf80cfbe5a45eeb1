#pragma once
// The host side of the serial protocol, without any I/O: commands go in,
// bytes for the port come out, the printer's lines go back in, and the sender
// decides what to send next. The event loop around it (send_session.hpp) only
// moves bytes and time.
//
// It does the handshake (handshake.hpp: M110 N0, M115),
// numbers and checksums every command and keeps a history for resends
// (resend.hpp), counts answers exactly (in_flight.hpp: each "ok" frees what
// it answers for), asks with M105 when an answer is overdue or the link is
// silent (probe_backoff.hpp, answer_clock.hpp), paces moves to the planner
// (pacer.hpp), checks each command before numbering it (line_check.hpp) and
// ends with M400. How and why, case by case: docs/gc-send-sender.md.
#include <cstdint>
#include <algorithm>
#include <array>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/firmware.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/report/estimator.hpp"
#include "gcode/serial/protocol/answer_clock.hpp"
#include "gcode/serial/protocol/flow_control.hpp"
#include "gcode/serial/protocol/in_flight.hpp"
#include "gcode/serial/protocol/line_check.hpp"
#include "gcode/serial/protocol/numbered_command.hpp"
#include "gcode/serial/protocol/pacer.hpp"
#include "gcode/serial/protocol/probe_backoff.hpp"
#include "gcode/serial/protocol/protocol.hpp"
#include "gcode/serial/protocol/resend.hpp"
#include "gcode/serial/protocol/reset_sequence.hpp"
#include "gcode/serial/sender/handshake.hpp"
#include "gcode/serial/sender/homing_watch.hpp"
#include "gcode/serial/sender/relocator.hpp"
#include "gcode/serial/sender/reset_recovery.hpp"

namespace gcode::serial {

struct SenderConfig {
  // Which commands take long or answer at once, how the firmware answers
  // (never null).
  const FirmwareFlavor* firmware = &marlin2_firmware();
  // The answer to M115 replaces `firmware` when its FIRMWARE_NAME names a
  // described flavour (find_firmware_by_report: Klipper, Prusa-Firmware,
  // RepRapFirmware, Marlin 1 or 2).
  bool firmware_from_report = true;
  FlowMode flow = FlowMode::Window;
  int queue = 4;             // Marlin BUFSIZE
  int rx_buffer = 128;       // Marlin RX_BUFFER_SIZE
  double timeout = 10;       // seconds without any sign of life before M105
  int max_timeouts = 5;      // consecutive silent rounds before giving up
  int max_resends = 10;      // requests for one line before giving up
  double link_bytes_per_second = 25000;  // baud / 10 (0: unknown, a pseudo-terminal)
  double time_scale = 1;     // a simulated printer's seconds per wall second
  int planner_blocks = 15;   // moves Marlin's planner holds: BLOCK_BUFFER_SIZE 16 less the empty one (learnt from ADVANCED_OK's P)
  std::size_t max_line = kDefaultMaxLine;  // Marlin MAX_CMD_SIZE
  bool max_line_from_firmware = true;      // an M115 report replaces max_line
  bool skip_bad_lines = false;             // leave out lines the firmware cannot take
  std::size_t read_ahead = 512;  // commands taken ahead of what is sent (gc-send: a few, so a
                                 // stage switched on mid-stream changes what follows at once)
  // Hold no more moves ahead of the nozzle than the printer's planner
  // takes (pacer.hpp), so a pause stops after what the planner holds
  // (background.md §1: 16 x 0.2 mm), and the printer still never waits for a line.
  bool pace = false;
  bool handshake = true;     // M110 N0 + M115 before the first line
  // After a reset the print goes on with X and Y homed alone (never Z: the
  // part is on the bed). False: a delta, which homes every tower at once:
  // the print stops and says how gc-relayer --resume-from-z finishes it.
  bool home_xy_alone = true;
  bool finish_with_m400 = true;
};

// How the sender times what it sends (Marlin's 16-block planner; heating
// and homing left out: nothing in a file bounds them): a time estimate of a
// whole file to hold against it is made with the same.
EstimatorOptions sender_estimator_options();

enum class SenderState : std::uint8_t { Idle, Handshake, Capabilities, Printing, Done, Failed, Cancelled };

enum class LogLevel : std::uint8_t { Trace, Info, Warning };  // Trace: every line both ways

struct SenderStats {
  std::uint64_t lines = 0;          // numbered lines sent (first time)
  std::uint64_t payload_bytes = 0;  // their bytes
  std::uint64_t bytes = 0;          // every byte written (resends, M105, handshake)
  std::uint64_t oks = 0;
  std::uint64_t resend_requests = 0;     // rewinds done
  std::uint64_t duplicate_resends = 0;   // repeated requests ignored
  std::uint64_t resent_lines = 0;        // lines sent again
  std::uint64_t errors = 0;              // Error: lines
  std::uint64_t ignored_resends = 0;     // requests for lines never sent
  std::uint64_t probes = 0;              // M105 sent because an answer was overdue
  std::uint64_t polls = 0;               // M105s sent (overdue answers and silent rounds)
  std::uint64_t pace_probes = 0;         // moves of no length the pacer asked with (pacer.hpp)
  std::uint64_t timeouts = 0;            // silent rounds of --timeout
  std::uint64_t busy = 0;
  std::uint64_t unknown = 0;
  std::uint64_t unknown_commands = 0;    // commands the firmware said it does not know
  std::uint64_t stray_oks = 0;           // an ok that answers for nothing in flight
  std::uint64_t shortened = 0;           // M117/M118 texts cut to fit
  std::uint64_t skipped = 0;             // lines left out (skip_bad_lines)
  std::uint64_t resets = 0;              // printer resets the print came back from
  std::uint64_t redone_moves = 0;        // moves sent again after them (they may print twice)
  double redone_mm = 0;                  // ... their length
  double print_start = -1;               // when the first numbered line went out
  double print_end = -1;                 // when the last ok came back
};

// Where the last acknowledged line came from, for "resume from here" messages.
struct Position {
  long long number = 0;          // the line number sent to the printer
  std::uint64_t source_line = 0; // the line in the input file (0: none)
  int layer = 0;                 // the layer it belongs to (0: start code)
};

class Sender : private TimeSink, private PrintHistory {
 public:
  // `input_line`: the input line a message is about (0: none).
  using Logger = std::function<void(LogLevel, std::uint64_t input_line, std::string_view)>;
  Sender(const SenderConfig& config, Logger log);

  void start(double now);
  // Logs every line sent and received (LogLevel::Trace).
  void set_trace(bool on) { trace_ = on; }

  // Input: commands as they go to the firmware (see command_for_sending).
  // Taken once the handshake is done, so they are checked against what the
  // firmware reported (its MAX_CMD_SIZE).
  bool wants_input() const {
    return state_ == SenderState::Printing && !input_done_ && pending() < std::min(kHighWater, config_.read_ahead);
  }
  void submit(std::string_view command, std::uint64_t source_line, int layer);
  void end_of_input();
  // The input had ended, but the print control adds lines of its own (a
  // cancel's safe end, a pause block in the end code): they are taken, and
  // end_of_input() ends the input again. Nothing after a refused line, a
  // cancel or the end of the print.
  void reopen_input();
  // Sends what the flow control allows now; call after submit/end_of_input.
  void pump(double now);

  // Output: bytes for the port.
  std::string_view output() const { return std::string_view(out_).substr(out_pos_); }
  void written(std::size_t n, double now);

  // A line from the printer (without its ending).
  void on_line(std::string_view line, double now);
  // Runs timers; call when `deadline()` has passed (or any time).
  void on_timer(double now);
  double deadline() const;

  // The port went away (unplugged board, closed pseudo-terminal).
  void disconnected(std::string_view why);
  // The port went away but may come back (gc-send --reconnect,
  // sender_relink.cpp): nothing is sent until link_back(), and what was on
  // its way is forgotten (the printer may or may not have it).
  void link_lost(double now);
  // The port is back: the printer is asked which line it took last (a
  // deliberately mis-numbered line: its "Last Line:") and where it stands
  // (M114). A printer that ran on and stands where that line left it
  // (within 0.01 mm) gets the next line; one that restarted, or stands
  // elsewhere, fails the print with a message that says so.
  void link_back(double now);
  bool relinking() const { return relocator_.active(); }

  // The printer's host actions (//action:pause, //action:resume); without a
  // handler a pause holds sending until the resume.
  using ActionHandler = std::function<void(std::string_view action)>;
  void set_action_handler(ActionHandler handler) { on_action_ = std::move(handler); }
  // The print cannot go on (homing_watch.hpp: the homing failed or was
  // lost): the handler ends it safely (heaters and motors off), and once
  // that is done the print fails with `why`. Without a handler the print
  // is cancelled (nothing more is sent) and fails.
  using LostHandler = std::function<void(std::string_view why)>;
  void set_lost_handler(LostHandler handler) { on_lost_ = std::move(handler); }
  // Why the print cannot go on (empty while it can).
  const std::string& lost() const { return lost_; }
  // The journal's hooks (send_journal.hpp): a command got its number, with
  // the machine state after it (called before its bytes can go out); the
  // printer acknowledged a numbered line.
  using Numbered = NumberedCommand;
  using NumberedHook = std::function<void(const Numbered&)>;
  using AcknowledgedHook = std::function<void(long long n)>;
  void set_journal_hooks(NumberedHook numbered, AcknowledgedHook acknowledged) {
    on_numbered_ = std::move(numbered);
    on_acknowledged_ = std::move(acknowledged);
  }
  // A resume (gc-send --resume): the printer kept running and expects line
  // `next` now, standing as `printer` says. Before start(), with the
  // handshake off: M110 N0 would throw away the numbering it goes on with
  // (M115 is still asked).
  // `track`: the print up to there (the journal's), for a reset later on;
  // `source_line`, `layer`: the input line and layer of command next - 1.
  void continue_from(long long next, const MachineState& printer, const ResumeTrack& track = {},
                     std::uint64_t source_line = 0, int layer = 0);
  // A resume after the printer reset (gc-send --resume, the journal's
  // resume plan): before start(), numbered on from `last_number` (M110 N
  // that), the lines that bring it back to the print (reset_sequence.hpp)
  // go out first, as going back to command `restore`; the input follows.
  void continue_after_reset(long long last_number, long long restore, int layer,
                            const std::vector<std::string>& sequence, const MachineState& target,
                            const ResumeTrack& track, std::uint64_t source_line = 0);
  // Nothing waits to be sent and nothing is in flight.
  bool idle() const { return pending() == 0 && flight_.empty() && output().empty(); }
  // The number the last submitted command got (0: none yet).
  long long last_submitted() const { return next_number_ - 1; }
  long long highest_sent() const { return highest_sent_; }
  // How often output not yet written was thrown away (a printer reset: the
  // restarted printer never gets it).
  std::uint64_t output_discards() const { return output_discards_; }
  // The printer's last temperature report ("T:205.00 /205.00 B:60.00 /60.00"; "" before one).
  const std::string& temperatures() const { return temperatures_; }

  // Takes back the newest commands not sent yet, at most `max` (a pause now
  // goes before them; they are submitted again after it): appended to
  // `commands` in order. `before` is the machine state before the first of
  // them (the sender's own model of the stream goes back to it). Returns
  // how many.
  std::size_t withdraw_unsent(std::size_t max, const MachineState& before, std::vector<std::string>& commands);

  // A cancel's safe end goes right after what is on its way: every command
  // handed over but not sent yet is dropped. Returns how many.
  std::size_t discard_unsent();

  // First Ctrl-C: send nothing more, wait for the lines in flight.
  void cancel();
  // Second Ctrl-C: M112 goes out at once, ahead of anything queued.
  void emergency_stop();

  SenderState state() const {
    return handshaking() && handshake_.step() == Handshake::Step::Capabilities ? SenderState::Capabilities : state_;
  }
  bool finished() const { return state_ == SenderState::Done || state_ == SenderState::Failed || (state_ == SenderState::Cancelled && output().empty()); }
  const std::string& failure() const { return failure_; }
  const SenderStats& stats() const { return stats_; }
  // Printer seconds of the moves handed over whose time is final (the
  // estimator's, as sender_estimator_options() sets it: no heating, no homing).
  double estimated_time() const { return estimator_.elapsed(); }
  const Position& last_acknowledged() const { return last_acked_; }
  const FirmwareInfo& firmware() const { return firmware_; }
  // The flavour in use: SenderConfig's, or the one the M115 answer named.
  const FirmwareFlavor& flavour() const { return *config_.firmware; }
  // The printer paused itself ("// action:paused", a flavour that reports
  // its own pause) and has not said it resumed.
  bool printer_paused() const { return printer_paused_; }
  const FlowControl& flow() const { return flow_; }
  std::size_t in_flight() const { return flight_.size(); }
  std::size_t pending() const { return static_cast<std::size_t>(next_number_ - next_send_); }
  bool cancelled() const { return cancelled_; }
  bool emergency() const { return emergency_; }
  // The link's bytes per second (0: unknown, a pseudo-terminal) and time
  // scale, as the firmware may have reported them.
  double link_bytes_per_second() const { return config_.link_bytes_per_second; }
  double time_scale() const { return config_.time_scale; }
  std::size_t max_line() const { return config_.max_line; }
  // "line 1234 of the input (layer 12)" for messages.
  std::string describe(const Position& p) const;

 private:
  static constexpr std::size_t kHighWater = 512;   // lines read ahead of the printer
  static constexpr long long kHistory = 512;       // sent lines kept for resends
  static constexpr double kNever = 1e300;
  // Printer seconds of motion a firmware that answers when a command is
  // queued (Klipper) holds before an answer waits (measured: about 1 s).
  static constexpr double kQueuedHold = 1.1;
  static constexpr std::string_view kProbe = "M105";  // asks for an answer that proves progress
  static constexpr std::string_view kPaceProbe = "G1";  // moves nothing: asks whether the planner is full

  // PrintStep: what a reset reads of it (reset_recovery.hpp).
  struct Slot : PrintStep {
    std::string wire;            // "N12 G1 X1*34\n"
    bool long_running = false;   // M109, G28, M400 ...: the answer may take long
    bool unbounded = false;      // M109, G28 ...: for a time nothing in the file tells
    bool silent_wait = false;    // waits for the user without a word (Prusa's M600)
    bool temperature_query = false;  // M105: answered in order with "ok T:..."
    bool instant = false;        // answered at once (G92, M104, G1 F1200 ...)
    bool homes = false;          // G28 (homing_watch.hpp)
    double motion = 0;           // printer seconds of moves (the estimator's once final)
    double nominal = 0;          // length / feed rate: no move takes less
    bool motion_final = false;
    bool closing = false;        // the closing M400 (the journal says so)
    // A line of the sender's own (an M105 question, a pace probe): numbered
    // like the file's, so line noise cannot make it another command; it
    // changes nothing, so it holds the state of the command before it.
    InFlight::Own own = InFlight::Own::None;
    std::uint64_t tag = 0;       // the estimator's name for it (its number may move up while unsent)
  };
  Slot& slot(long long n) { return ring_[static_cast<std::size_t>(n) & (ring_.size() - 1)]; }
  const Slot& slot(long long n) const { return ring_[static_cast<std::size_t>(n) & (ring_.size() - 1)]; }
  // PrintHistory: slot(n), or the resume's base (ResetRecovery::base).
  bool holds(long long n) const override { return in_history(n); }
  const PrintStep& step(long long n) const override { return slot(n); }
  const PrintStep& held(long long n) const override { return recovery_.is_base(n) ? recovery_.base() : slot(n); }
  long long first_held() const override { return first_held_; }
  void on_time(std::int64_t tag, double seconds) override;
  void grow_ring();
  void enqueue(std::string_view command, std::uint64_t source_line, int layer, bool closing = false);
  void refuse(std::uint64_t source_line, std::string why);
  void fill(double now);
  void send_unnumbered(std::string_view command);
  // A line of the sender's own goes out now, numbered next: the commands
  // numbered but not sent yet move up one number.
  bool room_for_own();
  void send_own(InFlight::Own kind, double now);
  long long make_room_for_own();
  void push_flight(long long number, std::size_t bytes, bool temperature_query,
                   InFlight::Own own = InFlight::Own::None);
  void journal_first_send(long long number);
  std::size_t own_line_bytes(std::string_view command) const;
  void acknowledge_front(double now, int planner_free = -1);
  void acknowledge_through(std::size_t index, double now, int planner_free = -1);
  void on_ok(const Response& r, double now);
  bool answers_handshake(const Response& r, double now);
  // (state_ is Handshake for both of its steps: handshake_ knows which.)
  bool handshaking() const { return state_ == SenderState::Handshake; }
  void on_resend(long long n, double now);
  void on_error(const Response& r, double now);
  void on_action(std::string_view action);
  void on_start(std::string_view text, double now);
  void on_capability(std::string_view text);
  void note_temperatures(const Response& r, std::string_view text);
  void set_link(double bytes_per_second, double time_scale);
  void fail(std::string message);
  void print_lost(std::string why);
  // The oldest line in flight (an error answers it), nullptr when that is
  // none of the file's.
  const Slot* oldest_file_line() const;
  void check_done(double now);
  void probe(double now, bool silent);
  void handshake_timer(double now);
  double current_timeout() const;
  double overdue_at() const;
  bool settled(double now) const;
  bool lines_in_flight() const { return flight_.lines() > 0; }
  bool long_command_in_flight() const;
  bool waiting_for_user() const;
  bool silent_command_in_flight() const;
  void detect_flavour();
  bool waiting_lines_fit(std::size_t max_line) const;
  // Pacing asked for, on a firmware whose answers can show its planner (not
  // one that answers as soon as a command is queued: Klipper's host queues
  // about 1 s of motion whatever the sender holds back, so holding moves
  // would only slow the print to the file's feed rates).
  bool pacing() const { return config_.pace && !config_.firmware->ok_when_queued; }
  bool paced(double now);
  void pace_probe(double now, std::size_t reserve);
  void planned(const Slot& s, const InFlight::Entry& f, double now, int planner_free);
  void log(LogLevel level, std::uint64_t input_line, std::string_view message) const;
  void relocate(long long expected, double now);
  bool check_position(std::string_view text, double now);
  void relink_ok(double now);
  void printer_reset(std::string_view how, double now);
  bool in_history(long long n) const {
    return n >= std::max(first_held_, next_send_ - kHistory) && n < next_number_;
  }
  // False when the print failed instead (a line no longer fits under its new number).
  bool resubmit_after_reset(long long restore, const std::vector<std::string>& sequence);
  void begin_handshake(double now);
  void restart_handshake(double now);
  void track(Slot& s, const Line& line, const Move& move);
  void took_back();

  SenderConfig config_;
  Logger log_;
  FlowControl flow_;
  SenderState state_ = SenderState::Idle;
  Handshake handshake_;
  std::string out_;
  std::size_t out_pos_ = 0;

  AnswerClock clock_;
  MachineState machine_;
  Estimator estimator_;
  std::vector<Slot> ring_;
  long long next_number_ = 1;   // the number the next submitted command gets
  long long next_send_ = 1;     // the next number to transmit
  long long highest_sent_ = 0;
  long long resent_above_highest_ = 0;  // make_room_for_own: sent lines moved past highest_sent_
  long long journaled_ = 0;     // the highest number the journal has a record of
  double queued_end_ = 0;       // when the answered moves end, by their estimates (Klipper's held oks)
  InFlight flight_;
  std::uint64_t out_total_ = 0;     // bytes ever put into out_
  std::uint64_t output_discards_ = 0;
  std::uint64_t written_total_ = 0; // bytes ever handed to the port
  std::uint64_t next_tag_ = 1;      // the estimator's name for the next command enqueued

  bool input_done_ = false;
  bool final_queued_ = false;
  bool cancelled_ = false;
  bool emergency_ = false;
  bool paused_ = false;         // //action:pause until //action:resume
  bool printer_paused_ = false; // "// action:paused" until "// action:resumed"
  bool told_user_wait_ = false; // said once that a wait for the user holds the timeouts
  bool pacing_off_said_ = false;  // detect_flavour(): "pacing off" said
  bool idle_hint_ = false;      // the printer said "wait" (idle) with lines in flight
  ProbeBackoff probes_;
  int learnt_planner_ = 0;      // planner blocks seen in ADVANCED_OK's P
  std::size_t written_off_ = 0; // answers to come for our M105s taken with an earlier one's
  std::string refusal_;         // why the input stopped early (a line the firmware cannot take)
  HomingWatch homing_;          // whether the printer can still move where the file says
  std::string lost_;            // why the print cannot go on (homing_watch.hpp)

  ResendState resend_;

  double last_rx_ = 0;          // last sign of life (an answer, busy, a heating report)
  double last_any_rx_ = 0;      // last byte of anything
  double last_busy_ = -1e9;
  int timeouts_in_row_ = 0;

  Relocator relocator_;  // after the port went away (sender_relink.cpp)

  // A reset's resume (sender_reset.cpp): what the print has done so far.
  long long last_enqueued_ = 0;     // the newest command in the print's order
  ResumeTrack track_;               // the print as numbered so far
  long long first_held_ = 1;        // the oldest number this sender numbered itself
  long long restoring_ = 0;         // numbering a resume's lines: the command they go back to
  ResetRecovery recovery_;          // the resume's base, and what a reset goes back to

  Position last_acked_;
  FirmwareInfo firmware_;
  SenderStats stats_;
  std::string failure_;
  bool trace_ = false;
  ActionHandler on_action_;
  LostHandler on_lost_;
  NumberedHook on_numbered_;
  AcknowledgedHook on_acknowledged_;
  std::string temperatures_;
  std::string moved_;  // room_for_own: a waiting line made anew under its next number
  Pacer pacer_;
};

}  // namespace gcode::serial
