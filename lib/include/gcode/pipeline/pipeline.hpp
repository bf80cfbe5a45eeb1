#pragma once
// The library's one loop: input -> lines -> MachineState and layers -> a
// chain of stages -> (usually) the writer. Every filter tool and gc-send run
// on it:
//
//   Pipeline pipeline(markers);
//   pipeline.add(subdivider);          // transforms and reports, in order
//   pipeline.add(writer);              // GcodeWriter: the output conventions
//   pipeline.run(input_fd);
//
// Work is done only where a stage asks for it: layers are tracked only when
// wanted, new lines are parsed and applied to a state only when a later
// stage reads lines or states, and a link keeps a state of its own only
// after a stage changed the stream (until the stream is back in step).
//
// Push style for event loops (gc-send): read_some(fd) whenever the input is
// readable; it returns false at the end of input, after finishing.
#include <cstddef>
#include <memory>
#include <string_view>
#include <vector>

#include "gcode/core/layer_marker.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gcode {

struct PipelineOptions {
  bool layers = true;           // track layers (else every line is start code, nothing is held)
  std::size_t block_size = 1 << 18;
};

class Pipeline : private LayerSink {
 public:
  explicit Pipeline(const LayerMarkers& markers, PipelineOptions options = {});
  ~Pipeline() override;
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  // The E mode of a file that never sets it (see e_mode.hpp); before the first line.
  void set_e_mode(bool relative) { tracker_.set_e_mode(relative); }
  // The input continues a stream that left the machine in `state` (its
  // position, modes, E coordinate, F): before the first line.
  void start_from(const MachineState& state) { tracker_.start_from(state); }
  // How its layers are found, when known from an earlier part of the same
  // file (LayerTracker::decide_mode): before the first line.
  void decide_layer_mode(LayerMode mode) { tracker_.decide_mode(mode); }
  // Buffers at least `bytes` of input from `fd` (less at its end) without
  // consuming it, and returns what is buffered; run() starts with it.
  std::string_view read_ahead(int fd, std::size_t bytes);

  // Appends a stage (not owned; it must outlive the pipeline's run).
  void add(Stage& stage);

  // Reads `fd` to its end through every stage, then finishes.
  void run(int fd);
  // Lines from memory (tests, small texts).
  void run_text(std::string_view text);
  // Push style: reads what `fd` has now and processes the complete lines;
  // false once the input has ended (and the stages are finished).
  bool read_some(int fd);
  // Push style from bytes already read.
  void feed(std::string_view bytes);
  // The end of the input: releases held lines and finishes every stage.
  void finish();
  // Ends the run before the input's end (the tool needs no more of it): a
  // line the last read cut off is not a line, the stages finish as usual.
  void finish_early();

  // Reads ahead without consuming: buffers input from `fd` until a motion
  // command has been seen or `max_bytes` are buffered (whichever first), and
  // returns the buffered text, so a tool can read a pipe's header (the
  // printer's bed, say) before its first byte goes out. run() starts with
  // these lines.
  std::string_view read_header(int fd, std::size_t max_bytes = 1 << 20);

  // The decimals the input uses per letter, as far as read (for stages that
  // write numbers: "the input's precision").
  const Precision& precision() const { return precision_; }
  const LayerTracker& tracker() const { return tracker_; }
  const std::string& feature_name(int id) const { return tracker_.feature_name(id); }
  bool finished() const { return finished_; }
  // Input read and not yet processed (what read_header/read_ahead buffered).
  std::string_view buffered() const { return splitter_.pending(); }
  // Bytes of input read so far.
  std::uint64_t bytes_read() const { return splitter_.bytes_received(); }

 private:
  void on_layer(const LayerInfo& layer, const MachineState& before) override;
  void on_end_code(std::uint64_t first_line, std::uint64_t offset, const MachineState& before) override;
  void on_line(const TrackedLine& line) override;
  void wire();
  void drain();
  void finish_stages();

  PipelineOptions options_;
  LayerTracker tracker_;
  Precision precision_;
  LineSplitter splitter_;
  std::vector<Stage*> stages_;
  std::vector<std::unique_ptr<Emitter>> links_;  // links_[0] feeds stages_[0]
  bool wired_ = false;
  bool finished_ = false;
};

}  // namespace gcode
