#pragma once
// What gc-send does with a print while it runs: pause and resume, cancel,
// speed, commands typed while paused. It sits at the end of the pipeline
// (send_session.hpp hands it every line with its state) and in front of the
// Sender, and holds lines back while the print is paused.
//
// pause      the rest of the current layer is rushed (a speed stage switched
//            on now, off at the layer's end: --rush, capped by --max-speed and
//            --max-flow); at the next layer event, before any line of the next
//            layer, the pause block of pause_sequence.hpp goes out (retract,
//            lift, park at the back, standby); then nothing until resume. In
//            the start code the pause comes before layer 1; in the end code at
//            once.
// pause now  the pause block goes out after the last command handed to the
//            sender: what the printer already holds still runs, nothing more.
// resume     the resume block (heat, back at the safe height, down to the
//            exact Z, unretract, E coordinate, modes, F); first, whatever the
//            commands typed while paused changed (position, modes, E,
//            temperature) is put back the way the block expects it.
// swap FILE  FILE (re-sliced with other settings) continues the print by
//            gc-relayer's rules (join_stream.hpp) from its first layer above
//            what is printed: at the next layer's start, or when paused at a
//            layer's start (nothing of it printed yet), at the resume, after
//            the resume block has taken the head back to where it paused. The
//            rest of the current file is left out; the session feeds FILE's
//            text from there (on_swap).
// In-stream pauses (@pause, ;@pause, --pause-on M0,...) are the file's own:
// whatever the file does around them (gc-pause-at writes its park and
// return there) is sent as it is; the host only holds the lines after it.
//
// cancel object ID|NAME  the object is left out from the next line on, also
//            in the middle of its block (object_cancel.hpp), and the print
//            goes on with the others; `objects` lists them.
//
// The printer's own //action:pause (its pause button with host actions) is a
// `pause`, //action:resume a `resume`, //action:cancel a `cancel`.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/serial/control/control_verbs.hpp"
#include "gcode/serial/control/object_cancel.hpp"
#include "gcode/serial/control/pause_log.hpp"
#include "gcode/serial/control/pause_reentry.hpp"
#include "gcode/serial/control/take_back.hpp"
#include "gcode/serial/sender/sender.hpp"
#include "gcode/transform/join_stream.hpp"
#include "gcode/transform/pause_context.hpp"
#include "gcode/transform/seam.hpp"
#include "gcode/transform/speed.hpp"

namespace gcode::serial {

struct PrintControlConfig {
  PauseConfig pause;            // the block (method None: gc-send waits itself)
  ParkRules park;               // where (the file's bed unless --park/--bed)
  double rush = 3;              // the rest of the layer after a pause request
  double max_speed = 0;         // caps on the rush, mm/s (0: none)
  double max_flow = 0;          // mm^3/s
  double filament_diameter = 1.75;
  std::vector<int> pause_on;    // M numbers handled as host pauses, not sent
  std::string cancel_gcode = "M104 S0\nM140 S0\nM107\nM84";  // after the park of a cancel
  SeamOptions seam;             // the way onto a swapped-in file
  std::vector<std::string> exclude;  // --exclude: objects left out from the start
};

enum class PrintState : std::uint8_t { Printing, Pausing, Paused, Cancelling };
std::string_view print_state_name(PrintState state);

// Exact figures a simulated printer can give about a pause (optional).
struct MotionProbe {
  std::function<double()> now;                 // printer seconds
  std::function<double(double)> travelled;     // path (mm) travelled by then
  std::function<void(long long)> watch;        // the first command of the pause block
  // When the motion ahead of the watched command ended and the path queued
  // before it; false while it has not run yet.
  std::function<bool(double&, double&)> watched;
};

class PrintControl {
 public:
  PrintControl(const PrintControlConfig& config, Sender& sender, Diagnostics& diagnostics, const Precision& precision);

  // The object excluder and the speed stages (`speed F`, the rush), to be
  // added to the pipeline before the sending stage, in this order.
  // `line_offset`: input lines before the pipeline's first (a resume, a swap);
  // `resumed_layer`: the layer a resume's pipeline starts inside (0: none).
  void add_stages(Pipeline& pipeline, std::uint64_t line_offset = 0, int resumed_layer = 0);
  void set_probe(MotionProbe probe) { probe_ = std::move(probe); }

  // Every call that can start or end a pause is given `now`, the caller's
  // clock as the Sender is given it (wall seconds in gc-send, a script's
  // clock in a test): the pause log's times are on it.
  //
  // From the sending stage: every line, layer start and the end code.
  void line(const TrackedLine& t, double now);
  void layer(const LayerInfo& info, const MachineState& before, double now);
  void end_code(const MachineState& before, double now);
  // The input has ended (everything held is sent once resumed).
  void end_of_input(double now);

  // Whether the sending stage may take more input (not holding).
  bool accepts_input() const { return !holding_ && state_ != PrintState::Cancelling; }
  // Whether the sender may be told the input has ended.
  bool input_may_end() const { return !holding_ && held_.empty(); }

  void command(const ControlCommand& c, double now);
  // The printer's //action: text.
  void action(std::string_view text, double now);
  // Ctrl-C: the first cancels; returns false from the second on.
  bool interrupt();
  // The printer cannot move where the file says (Sender::set_lost_handler):
  // the print ends with heaters and motors off and no park (a move would
  // be refused).
  void lost(std::string_view why, double now);
  // Call after the sender moved: notes when a pause block is done.
  void update(double now);

  PrintState state() const { return state_; }
  // "paused" only once the printer has done the block.
  std::string_view state_label() const;
  int layer() const { return layer_; }
  const std::vector<PauseRecord>& pauses() const { return pauses_.records(); }
  bool cancelled() const { return state_ == PrintState::Cancelling; }
  std::uint64_t user_commands() const { return user_commands_; }
  std::uint64_t host_commands() const { return host_commands_; }
  double speed() const { return speed_; }
  // Called for `status` and when a pause is reached.
  std::function<void()> on_status;
  // A swap starts: from now on the session feeds `next`'s text (it stands
  // where the printer stands now) instead of the current input; `layers_done`
  // layers are printed. Without it, swap is refused.
  std::function<void(std::unique_ptr<JoinStream> next, int layers_done)> on_swap;
  const SeamOptions& seam_options() const { return config_.seam; }
  std::uint64_t swaps() const { return swaps_; }
  // The objects cancelled (`cancel object`, --exclude, the journal's).
  ObjectCancel& objects() { return objects_; }
  const ObjectCancel& objects() const { return objects_; }
  // gc-send --resume of a print that stood paused (pause_reentry.hpp):
  // the printer stands `parked` (the journal's state after the pause block
  // and anything typed), the print stopped at `at` (with `retracted` mm of
  // its own retraction pending and `top_z` printed). The control waits for
  // `resume`, whose way back is the pause block's for `at` from there.
  // `taken`: the lines of the pause block that ran; when gc-send stopped
  // inside it, the rest goes out first, and the head parks as it would have:
  // returns how many lines of it that is.
  std::size_t resume_into_pause(const MachineState& at, const MachineState& parked, double retracted, double top_z,
                                std::size_t taken, double now);
  // gc-send --resume inside layer `layer` (the journal's): the lines up to
  // the next layer are of it, not start code.
  void continue_in_layer(int layer) {
    layer_ = layer;
    region_ = Region::Layer;
  }
  // The `speed F` the print had (the journal's), before anything is sent.
  void restore_speed(double factor) {
    if (factor > 0 && factor != 1) set_speed(factor);
  }
  // Wall seconds the printer stood paused (the block done until the resume),
  // the pause going on included.
  double paused_seconds(double now) const;

 private:
  // The verbs' handlers (control_verbs.cpp) call the actions below.
  friend std::span<const ControlVerb> control_verbs();

  // A line of the file held back while paused (or cancelling).
  struct Held {
    std::string command;     // as sent ("" for an in-stream pause)
    std::uint64_t source = 0;
    int layer = 0;
    MachineState after;
    bool host_pause = false;
    bool extruding = false;
  };
  // Where a pause stopped the print, and what its resume must undo.
  struct Stop {
    MachineState at;             // the stream where the print stopped (before any block)
    PauseContext printed;        // what was printed there (held lines are observed after it)
    MachineState resume_from;    // what the resume block starts from (the block's end, or `at`)
    MachineState printer;        // the printer while paused: resume_from and the commands typed since
    std::vector<std::string> resume_lines;  // the block's way back (own_block)
    bool own_block = false;      // the pause is ours (a block to undo), not the file's
  };
  void process(std::string_view command, std::uint64_t source, int layer, const MachineState& after, bool host_pause,
               bool extruding);
  void submit_lines(const std::vector<std::string>& lines, int layer);
  void submit_typed(std::string_view command);
  void track(std::string_view line, MachineState& state) const;
  void request_pause(std::string request, bool now);
  void finish_pausing(const MachineState& at);
  void pause_here(const MachineState& at);
  PauseConfig pause_config(const MachineState& at) const;
  void hold_here(std::string request);
  void stop_at(const MachineState& at, const MachineState& resume_from, bool own_block);
  void resume();
  void cancel(bool move_away = true);
  std::vector<std::string> safe_end(const MachineState& at, bool parked);
  void user_gcode(const std::string& text);
  void insert_file(const std::string& path);
  void set_speed(double factor);
  void request_swap(const std::string& path);
  bool at_layer_start() const;
  bool swap_here(const MachineState& at, const PauseContext& context, int layers_done);
  void withdraw_unsent();
  void forget_sent();
  void forget_recent();
  bool can_rewind(std::size_t n);
  std::vector<TakeBackLedger::Entry> rewind(std::size_t n);
  std::vector<std::string> put_back(const MachineState& from, const MachineState& to) const;
  PauseRecord& start_record(std::string request);

  PrintControlConfig config_;
  Sender& sender_;
  Diagnostics& diag_;
  const Precision& precision_;
  SpeedStage user_speed_;
  SpeedStage rush_;
  ObjectCancel objects_;
  MotionProbe probe_;
  double now_ = 0;  // the `now` of the call being handled

  PrintState state_ = PrintState::Printing;
  bool holding_ = false;
  bool input_ended_ = false;
  int layer_ = 0;
  Region region_ = Region::StartCode;
  int interrupts_ = 0;
  // The stream as handed to the sender: its state after the last command,
  // what it printed (the pause context) after it and before the line being
  // handled, and that command's input line.
  MachineState handed_;
  PauseContext printed_;
  PauseContext printed_before_line_;
  std::uint64_t last_source_ = 0;
  bool sent_extrusion_ = false;      // an extruding move went out since the last layer's start
  Stop stop_;                        // while paused (or holding)
  std::deque<Held> held_;
  TakeBackLedger ledger_;
  PauseLog pauses_;
  std::string scratch_;
  std::uint64_t user_commands_ = 0;
  std::uint64_t host_commands_ = 0;
  double speed_ = 1;
  std::unique_ptr<JoinStream> swap_; // asked for, not started yet
  std::uint64_t swaps_ = 0;
};

}  // namespace gcode::serial
