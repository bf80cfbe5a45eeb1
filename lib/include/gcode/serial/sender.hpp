#pragma once
// The host side of the serial protocol, without any I/O: commands go in,
// bytes for the port come out, the printer's lines go back in, and the sender
// decides what to send next. The event loop around it (send_session.hpp) only
// moves bytes and time.
//
// What it takes care of:
//  * handshake: "M110 N0" until the firmware answers, then "M115" for its
//    capabilities (ADVANCED_OK, EMERGENCY_PARSER, ...);
//  * numbering: every command goes out as "N<n> <command>*<checksum>" and
//    stays in a history until no resend can ask for it any more;
//  * flow control (flow_control.hpp): each "ok" frees the oldest line in
//    flight (Marlin answers in order); with ADVANCED_OK, "ok N<n>" frees all
//    lines up to n;
//  * resends: "Resend: n" rewinds to line n. Marlin empties its receive
//    buffer after a bad line, and every line still on the wire then fails
//    too and asks for the same n again (each with its own "ok"), and each of
//    those empties the buffer again, taking any early copy of line n with it.
//    Stale lines wait in the buffer while a move blocks on a full planner,
//    so silence alone proves nothing. After a rewind the sender therefore
//    waits until every line before n is acknowledged (the queue is empty, so
//    the firmware reads each arriving line at once) and the link has then
//    been quiet for a few byte times; it ignores repeated requests for n
//    meanwhile, and only then sends line n again. The "ok" after each Resend
//    belongs to the rejected line and frees nothing;
//  * counting answers exactly: every line in flight gets one answer, in
//    order, and each "ok" frees what it answers for: the "ok" right after a
//    "Resend:" belongs to the rejected line and frees nothing; "ok T:" (the
//    answer to M105) frees every line up to that M105; with ADVANCED_OK,
//    "ok N<n>" frees every line up to n and an "ok" without N frees none;
//    an "ok" with nothing in flight is counted as stray. Where a stream
//    could mean two things, the sender assumes the one that frees less: a
//    line believed in flight costs one quick question (below), a line freed
//    too early could overrun the printer's buffer;
//  * lost answers: the expected "ok" is overdue when the line has crossed
//    the link, the answer before it has come, the planner has had time to
//    make room (answer_clock.hpp: from the moves' estimated times) and a
//    margin has passed; then "M105" goes out at once. Marlin answers it in
//    order with "ok T:...", which proves every earlier line was executed, so
//    its answer acknowledges them all (the "ok" that got lost is counted as
//    received, as OctoPrint does). At most three such questions go out in a
//    row, each waiting twice as long as the one before and only if it fits
//    into the printer's buffer (room for one is always kept); "ok T:"
//    answers the oldest. Heating, homing and other waits of unknown length
//    are overdue only when the printer's "busy:" or temperature reports
//    stop; a printer that says "wait" (idle) is asked at once;
//  * timeouts: no sign of life for `timeout` seconds (longer while a long
//    command runs) also sends "M105"; after `max_timeouts` such silent
//    rounds in a row the sender gives up, naming the last acknowledged line;
//  * input: each command is checked before it is numbered (line_check.hpp):
//    an over-long M117/M118 text is shortened, any other line the firmware
//    cannot take stops the print before it (or is left out with
//    skip_bad_lines); an input without a command is a failure, not a print;
//  * the end: after the last line, "M400" and its "ok" (the printer is idle).
#include <cstdint>
#include <algorithm>
#include <array>
#include <deque>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/machine_state.hpp"
#include "gcode/report/estimator.hpp"
#include "gcode/serial/answer_clock.hpp"
#include "gcode/serial/flow_control.hpp"
#include "gcode/serial/line_check.hpp"
#include "gcode/serial/protocol.hpp"

namespace gcode::serial {

struct SenderConfig {
  FlowMode flow = FlowMode::Window;
  int queue = 4;             // Marlin BUFSIZE
  int rx_buffer = 128;       // Marlin RX_BUFFER_SIZE
  double timeout = 10;       // seconds without any sign of life before M105
  int max_timeouts = 5;      // consecutive silent rounds before giving up
  int max_resends = 10;      // requests for one line before giving up
  double link_bytes_per_second = 25000;  // baud / 10 (0: unknown, a pseudo-terminal)
  double time_scale = 1;     // a simulated printer's seconds per wall second
  int planner_blocks = 16;   // Marlin BLOCK_BUFFER_SIZE (learnt from ADVANCED_OK's P)
  std::size_t max_line = kDefaultMaxLine;  // Marlin MAX_CMD_SIZE
  bool max_line_from_firmware = true;      // an M115 report replaces max_line
  bool skip_bad_lines = false;             // leave out lines the firmware cannot take
  std::size_t read_ahead = 512;  // commands taken ahead of what is sent (gc-send: a few, so a
                                 // stage switched on mid-stream changes what follows at once)
  // Hold no more moves ahead of the nozzle than the printer's planner takes:
  // a move goes out only while the moves in flight and those the planner
  // still holds are fewer than its blocks. What the planner holds comes
  // from the answers: each answered move entered it then, and runs for its
  // length at its feed rate after the one before (the fastest it can go,
  // so the count never runs high and the planner is never starved by it).
  // So a pause stops after what the planner holds (background.md §1:
  // 16 x 0.2 mm), and the printer still never waits for a line.
  bool pace = false;
  bool handshake = true;     // M110 N0 + M115 before the first line
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
  std::uint64_t timeouts = 0;            // silent rounds of --timeout
  std::uint64_t busy = 0;
  std::uint64_t unknown = 0;
  std::uint64_t stray_oks = 0;           // an ok that answers for nothing in flight
  std::uint64_t shortened = 0;           // M117/M118 texts cut to fit
  std::uint64_t skipped = 0;             // lines left out (skip_bad_lines)
  double print_start = -1;               // when the first numbered line went out
  double print_end = -1;                 // when the last ok came back
};

// Where the last acknowledged line came from, for "resume from here" messages.
struct Position {
  long long number = 0;          // the line number sent to the printer
  std::uint64_t source_line = 0; // the line in the input file (0: none)
  int layer = 0;                 // the layer it belongs to (0: start code)
};

struct FirmwareInfo {
  std::string name;              // FIRMWARE_NAME
  bool advanced_ok = false;
  bool emergency_parser = false;
  bool autoreport_temp = false;
  bool busy_protocol = false;
  double time_scale = 0;         // TIME_SCALE: a simulated printer runs this much faster
  double baud = 0;               // BAUD: a simulated printer's link rate
  std::size_t max_line = 0;      // Cap:MAX_CMD_SIZE (Marlin does not report it)
};

class Sender : private TimeSink {
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

  // The printer's host actions (//action:pause, //action:resume); without a
  // handler a pause holds sending until the resume.
  using ActionHandler = std::function<void(std::string_view action)>;
  void set_action_handler(ActionHandler handler) { on_action_ = std::move(handler); }
  // Nothing waits to be sent and nothing is in flight.
  bool idle() const { return pending() == 0 && flight_.empty() && output().empty(); }
  // The number the last submitted command got (0: none yet).
  long long last_submitted() const { return next_number_ - 1; }
  long long highest_sent() const { return highest_sent_; }
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

  SenderState state() const { return state_; }
  bool finished() const { return state_ == SenderState::Done || state_ == SenderState::Failed || (state_ == SenderState::Cancelled && output().empty()); }
  const std::string& failure() const { return failure_; }
  const SenderStats& stats() const { return stats_; }
  // Printer seconds of the moves handed over whose time is final (the
  // estimator's, as sender_estimator_options() sets it: no heating, no homing).
  double estimated_time() const { return estimator_.elapsed(); }
  const Position& last_acknowledged() const { return last_acked_; }
  const FirmwareInfo& firmware() const { return firmware_; }
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
  static constexpr double kQuietStart = 0.05;      // quiet link after M115 before the first line
  static constexpr double kNever = 1e300;
  static constexpr std::string_view kProbe = "M105";  // asks for an answer that proves progress
  static constexpr int kQuickProbes = 3;  // overdue answers asked for in a row before only --timeout asks

  struct Slot {
    std::string wire;            // "N12 G1 X1*34\n"
    std::uint64_t source_line = 0;
    int layer = 0;
    bool long_running = false;   // M109, G28, M400 ...: the answer may take long
    bool unbounded = false;      // M109, G28 ...: for a time nothing in the file tells
    bool temperature_query = false;  // M105: answered in order with "ok T:..."
    bool move = false;           // takes a planner block (its ok comes when it has one)
    bool instant = false;        // answered at once (G92, M104, G1 F1200 ...)
    double motion = 0;           // printer seconds of moves (the estimator's once final)
    double nominal = 0;          // length / feed rate: no move takes less
    bool motion_final = false;
  };
  struct Flight {
    long long number;            // -1: an unnumbered command (M105 asked by the sender)
    std::uint32_t bytes;
    bool temperature_query;
    std::uint64_t end;           // output offset just after its last byte
    double arrival;              // when it reached the printer (kNever: not written yet)
  };

  Slot& slot(long long n) { return ring_[static_cast<std::size_t>(n) & (ring_.size() - 1)]; }
  const Slot& slot(long long n) const { return ring_[static_cast<std::size_t>(n) & (ring_.size() - 1)]; }
  void on_time(std::int64_t tag, double seconds) override;
  void grow_ring();
  void enqueue(std::string_view command, std::uint64_t source_line, int layer);
  void refuse(std::uint64_t source_line, std::string why);
  void fill(double now);
  void send_unnumbered(std::string_view command, bool temperature_query, bool track);
  void push_flight(long long number, std::size_t bytes, bool temperature_query);
  void acknowledge_front(double now);
  void acknowledge_through(std::size_t index, double now);
  void on_ok(const Response& r, double now);
  void on_resend(long long n, double now);
  void on_capability(std::string_view text);
  void set_link(double bytes_per_second, double time_scale);
  void fail(std::string message);
  void check_done(double now);
  void probe(double now, bool silent);
  double current_timeout() const;
  double overdue_at() const;
  bool settled(double now) const;
  bool lines_in_flight() const;
  std::size_t flight_lines() const;
  bool probing() const;
  bool paced(double now);
  void planned(const Slot& s, double now);
  void log(LogLevel level, std::uint64_t input_line, std::string_view message) const;

  SenderConfig config_;
  Logger log_;
  FlowControl flow_;
  SenderState state_ = SenderState::Idle;
  std::string out_;
  std::size_t out_pos_ = 0;

  AnswerClock clock_;
  MachineState machine_;
  Estimator estimator_;
  std::vector<Slot> ring_;
  long long next_number_ = 1;   // the number the next submitted command gets
  long long next_send_ = 1;     // the next number to transmit
  long long highest_sent_ = 0;
  std::deque<Flight> flight_;
  std::size_t flight_bytes_ = 0;
  std::uint64_t out_total_ = 0;     // bytes ever put into out_
  std::uint64_t written_total_ = 0; // bytes ever handed to the port

  bool input_done_ = false;
  bool final_queued_ = false;
  bool cancelled_ = false;
  bool emergency_ = false;
  bool paused_ = false;         // //action:pause until //action:resume
  bool expect_error_ok_ = false;
  bool caps_answered_ = false;
  bool idle_hint_ = false;      // the printer said "wait" (idle) with lines in flight
  int probes_in_row_ = 0;       // questions without an answer: each waits twice as long
  double next_probe_ = 0;       // no question before this
  int learnt_planner_ = 0;      // planner blocks seen in ADVANCED_OK's P
  std::string refusal_;         // why the input stopped early (a line the firmware cannot take)

  bool settling_ = false;
  long long settle_line_ = -1;
  double settle_from_ = 0;
  double settle_quiet_ = 0;
  long long resend_line_ = -1;
  int resend_count_ = 0;

  double last_rx_ = 0;          // last sign of life (an answer, busy, a heating report)
  double last_any_rx_ = 0;      // last byte of anything
  double last_busy_ = -1e9;
  double handshake_start_ = 0;
  double handshake_retry_ = 0;
  int timeouts_in_row_ = 0;

  Position last_acked_;
  FirmwareInfo firmware_;
  SenderStats stats_;
  std::string failure_;
  bool trace_ = false;
  ActionHandler on_action_;
  std::string temperatures_;
  // Pacing: when the last answered moves end at the earliest (ring of the
  // planner's size), and when a blocked move may go.
  std::array<double, 64> pace_ends_{};
  std::size_t pace_next_ = 0;
  double pace_last_end_ = 0;
  double pace_wait_ = 1e300;
};

}  // namespace gcode::serial
