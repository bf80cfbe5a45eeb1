#pragma once
// gc-send's pipeline in one event loop: G-code from the input runs through
// the library's pipeline (pipeline.hpp: lines, state, layers, the speed
// stages of print_control.hpp), whose last stage hands commands to the
// PrintControl and through it to the Sender; the Sender's bytes go to the
// port, the port's lines back to the Sender; the control FIFO's commands go
// to the PrintControl; a timer writes the progress.
//
// The input is fed to the pipeline one line at a time, and only while the
// sender wants more: what a stage switched on mid-stream changes (the rush
// of a pause) is what follows the request, not what was read long before.
// Ctrl-C once cancels (a safe end); Ctrl-C twice sends M112 at once.
//
// A swap (print_control.hpp) leaves the input for good: the other file's
// text (join_stream.hpp) runs through a pipeline of its own, started where
// the printer stands, with the same speed stages and the same control; its
// layers count on from those printed.
#include <signal.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/e_mode.hpp"
#include "gcode/core/layer_marker.hpp"
#include "gcode/core/print_area.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/serial/control/control_fifo.hpp"
#include "gcode/serial/control/print_control.hpp"
#include "gcode/serial/job/port_reconnect.hpp"
#include "gcode/serial/job/progress.hpp"
#include "gcode/serial/journal/input_hash.hpp"
#include "gcode/serial/journal/send_journal.hpp"
#include "gcode/serial/link/event_loop.hpp"
#include "gcode/serial/link/port.hpp"
#include "gcode/serial/sender/sender.hpp"

namespace gcode::serial {

class SendSession : private Stage {
 public:
  // Does not own the descriptors. `port_fd` is made non-blocking. `markers`:
  // where the input's layers begin (the slicers' markers, or --layer-marker's).
  SendSession(EventLoop& loop, Sender& sender, int input_fd, int port_fd, Diagnostics& diagnostics,
              LayerMarkers markers = LayerMarkers());
  ~SendSession() override;
  SendSession(const SendSession&) = delete;
  SendSession& operator=(const SendSession&) = delete;

  // The bed and height the file states (its header, or for a regular file
  // its head and tail), before anything is sent.
  PrintArea read_print_area();
  // The E mode of an input that never says M82/M83 (e_mode.hpp), before
  // anything is sent: `choice`, else guessed with a warning naming `name`.
  // A regular file is read at both ends; from a pipe only the lines before
  // the first move, so the print is not held back to read ahead. Returns
  // 1 relative, 0 absolute, -1 the file says itself.
  int read_e_mode(EModeChoice choice, std::string_view name);
  const LayerMarkers& markers() const { return markers_; }
  // Pausing, cancelling, speed: before run(). `control_path` empty: no FIFO.
  void set_control(const PrintControlConfig& config, const std::string& control_path);
  void set_progress(const ProgressOptions& options) { progress_.emplace(options, diag_); }
  // The layers of the whole input, when known beforehand (a regular file).
  void set_total_layers(int layers) { total_layers_ = layers; }
  // The estimator's printer seconds for the whole input (sender_estimator_options),
  // when known beforehand: the ETA goes by it.
  void set_estimated_time(double seconds) { eta_.set_estimate(seconds); }
  // Keeps the journal (not owned) while printing: before run().
  void set_journal(SendJournal* journal);
  // A resume: the input's first `bytes` were printed before (they are read
  // and hashed, not fed), its lines count on from `lines`, its layers from
  // `layer`, and the pipeline starts where the machine stood (`state`).
  // `hash_bytes`: how many of the first bytes skipped_hash() covers (a
  // checkpoint of the journal, maybe a little past `bytes`).
  void skip_printed(std::uint64_t bytes, std::uint64_t hash_bytes, std::uint64_t lines, int layer,
                    const MachineState& state);
  // The hash of the input's first `hash_bytes` (0 when the input ended before).
  std::uint64_t skipped_hash() const { return input_hash_.check_digest(); }
  std::uint64_t skipped_bytes() const { return skipped_bytes_; }
  // A port that fails (EIO, ENODEV, a hang-up) is waited for up to
  // `seconds` at `path` and opened again with `options` (no DTR reset):
  // port_reconnect.hpp. Without it (or with 0 s) a lost port ends the
  // print at once.
  void set_reconnect(const std::string& path, const PortOptions& options, double seconds);
  // Once the port was lost with --reconnect the session closed the
  // descriptor it was given, and closes those it opens itself.
  bool port_replaced() const { return port_replaced_; }
  bool reconnecting() const { return reconnect_ && reconnect_->waiting(); }
  PrintControl* control() { return control_.get(); }
  const ControlFifo* fifo() const { return fifo_.get(); }

  // Runs until the sender is finished.
  void run();
  std::uint64_t input_lines() const { return input_lines_; }
  int layers() const;
  bool emergency() const { return interrupts_ > 1; }

 private:
  // The last stage: what reaches it is sent (through the control).
  void line(const TrackedLine& t, Emitter& out) override;
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) override;
  bool reads_state() const override { return true; }
  struct Segment;
  void deliver(const TrackedLine& t, int layer_offset, std::uint64_t line_offset, int resumed_layer = 0);
  bool same_layer_again(const LayerInfo& info);
  void start_swap(std::unique_ptr<JoinStream> next, int layers_done);
  bool feed_segment();
  void read_input();
  void hash_fed(std::string_view bytes);
  void count_header();
  void feed_input();
  void read_port();
  void flush_port();
  void watch_port();
  void port_lost(std::string_view why);
  void try_reconnect(double now);
  std::string_view state_label() const;
  void on_signal();
  void update();
  void note_live_control();
  void report(bool force);
  ProgressSnapshot snapshot() const;

  EventLoop& loop_;
  Sender& sender_;
  int input_fd_;
  int port_fd_;
  int signal_fd_ = -1;
  sigset_t saved_mask_{};  // the signal mask before the session blocked SIGINT and SIGTERM
  Diagnostics& diag_;
  LayerMarkers markers_;
  Pipeline pipeline_;
  std::unique_ptr<PrintControl> control_;
  std::unique_ptr<ControlFifo> fifo_;
  std::unique_ptr<ControlParser> parser_;
  std::optional<Progress> progress_;
  std::uint64_t input_lines_ = 0;
  std::uint64_t input_bytes_ = 0;   // fed to the pipeline
  std::uint64_t input_size_ = 0;    // a regular file's size (0: unknown)
  bool input_eof_ = false;
  bool input_done_ = false;         // the pipeline has finished
  std::string in_buf_;              // read, not yet fed
  std::size_t in_pos_ = 0;
  std::string port_in_;       // a partial line from the printer
  int input_watch_ = -1;
  int port_watch_ = -1;
  std::optional<PortReconnect> reconnect_;  // none: a lost port ends the print
  bool port_replaced_ = false;   // the caller's descriptor is closed; port_fd_ (if >= 0) is ours
  int interrupts_ = 0;
  double started_ = 0;
  double next_report_ = 0;
  std::string_view shown_state_;   // what the progress last showed
  int shown_layer_ = -1;
  int total_layers_ = 0;
  PrintEta eta_;
  // Swapped-in files, all kept: a swap starts inside a pipeline's call.
  std::vector<std::unique_ptr<Segment>> segments_;
  Segment* current_ = nullptr;  // what is fed now (null: the input)
  SendJournal* journal_ = nullptr;
  double journal_due_ = 0;         // the journal's next timed flush
  std::uint64_t line_base_ = 0;    // a resume: input lines before the first one fed
  int layer_base_ = 0;             // ... and layers printed before it
  int resumed_layer_ = 0;          // ... the layer it stopped in (the journal's; 0: the start code)
  double resumed_z_ = 0;           // ... and the nozzle's height there
  std::uint64_t skipped_bytes_ = 0;
  InputHash input_hash_;            // the input's bytes fed (or printed before a resume)
  std::uint64_t fed_lines_ = 0;     // input lines fed to the pipeline (a resume's not counted)
  PrintedObjects printed_objects_;  // a resume: the objects the printed part named
};

}  // namespace gcode::serial
