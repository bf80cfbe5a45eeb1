#pragma once
// A stage of the pipeline: one transform or report between the input and
// the writer (pipeline.hpp).
//
// A stage sees every line with its true state (the state of the lines it
// receives, after the stages before it changed them) and the layer events,
// in input order. For each it decides what goes on to the next stage through
// its Emitter: the line as it is (pass), nothing (drop), a changed line
// (replace), or new lines before or after it (insert). Reports are stages
// that pass everything and keep their figures; transforms are stages that
// change the stream. A stage can be switched off and on at any line (gc-send
// switches a speed stage on for "the rest of this layer").
//
// What a stage receives is valid during the call only: a stage that keeps a
// line for later copies its text.
#include <cstdint>
#include <string>
#include <string_view>

#include "gcode/core/layer_tracker.hpp"

namespace gcode {

class Stage;

struct EndCodeInfo {
  std::uint64_t first_line = 0;  // 0 when the end code holds no line
  std::uint64_t offset = 0;
};

// The way from one stage to the next. Owned by the pipeline.
class Emitter {
 public:
  Emitter() = default;
  Emitter(const Emitter&) = delete;
  Emitter& operator=(const Emitter&) = delete;

  // The line goes on unchanged.
  void pass(const TrackedLine& t);
  // The line goes on with new text (no ending: the input line's own ending is
  // kept, also a missing final one). Its comment is the caller's to keep
  // (LineEdit keeps it).
  void replace(const TrackedLine& t, std::string_view text);
  // A new line (text without an ending) after everything emitted so far:
  // before the current line if it was not passed yet, else after it. It is
  // written with the input's line ending.
  void insert(std::string_view text);
  // Several lines separated by '\n' ("\r\n" too); empty lines are skipped.
  void insert_lines(std::string_view text);
  // Layer events go on (a stage may also hold them back or make its own).
  void layer(const LayerInfo& info, const MachineState& before);
  void end_code(const EndCodeInfo& info, const MachineState& before);

  // The state after everything emitted so far (what an inserted line starts
  // from); valid until the next call into the pipeline.
  const MachineState& state() const { return *cursor_; }
  Region region() const { return line_ != nullptr ? line_->region : region_; }
  int layer_index() const { return line_ != nullptr ? line_->layer : layer_; }
  int feature() const { return line_ != nullptr ? line_->feature : feature_; }
  // The input line the current line or event came with (for messages).
  std::uint64_t input_line() const { return line_ != nullptr ? line_->raw.number : input_line_; }

 private:
  friend class Pipeline;
  void deliver(const TrackedLine& t);
  void pass_changed(const TrackedLine& t);
  void dropped(const TrackedLine& t);
  void deliver_new(std::string_view text, std::string_view ending, LineOrigin origin, const TrackedLine* from);

  Stage* next_ = nullptr;         // null: the end of the chain
  Emitter* next_out_ = nullptr;   // the next stage's emitter
  bool track_ = false;            // a later stage reads states: new lines are applied
  bool parse_ = false;            // a later stage reads parsed lines
  bool own_ = false;              // the stream here differs from upstream: this link keeps its own state
  const MachineState* cursor_ = nullptr;  // the stream's state here, now
  const TrackedLine* line_ = nullptr;     // the line being handled (the context of new lines), or null
  MachineState state_;            // the stream's state here while own_
  MachineState before_;
  std::string text_;              // the text of a new line while it is delivered
  // The context when no line is current (after an event).
  Region region_ = Region::StartCode;
  int layer_ = 0;
  int feature_ = -1;
  std::uint64_t input_line_ = 0;
};

class Stage {
 public:
  virtual ~Stage() = default;

  // One line; the default passes it on.
  virtual void line(const TrackedLine& t, Emitter& out) { out.pass(t); }
  // Just before the first line of a layer; `before` is the state there.
  virtual void layer(const LayerInfo& info, const MachineState& before, Emitter& out) { out.layer(info, before); }
  // Just before the first line of the end code (also when it is empty).
  virtual void end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) {
    out.end_code(info, before);
  }
  // The end of the input: a last chance to add lines.
  virtual void finish(Emitter& out) { (void)out; }

  // What the stage reads, so the pipeline does only the work someone needs:
  // a writer reads neither the parsed line nor the state.
  virtual bool reads_state() const { return true; }
  virtual bool reads_lines() const { return true; }

  // Switched off, the stage is skipped: lines go past it unchanged. A stage
  // that must finish something when switched off (restore a feed rate)
  // overrides this and switches itself off once done.
  virtual void set_enabled(bool on) { enabled_ = on; }
  bool enabled() const { return enabled_; }

 private:
  bool enabled_ = true;
};

// The hot path, inline: a line that goes on unchanged through a link that
// follows its input costs a check, two stores and the next stage's call.
inline void Emitter::deliver(const TrackedLine& t) {
  Emitter& out = *next_out_;
  if (!next_->enabled()) {
    // A switched-off stage is skipped: its output is its input.
    out.pass(t);
    return;
  }
  out.cursor_ = &t.before;
  out.line_ = &t;
  next_->line(t, out);
  // Dropped (nothing passed, replaced or inserted): the stream after the
  // stage stays where it was before the line.
  if (out.cursor_ == &t.before && out.track_ && !out.own_) out.dropped(t);
  // The line's views end here; an insert made later (finish) takes the
  // context of the last event.
  out.line_ = nullptr;
}

inline void Emitter::pass(const TrackedLine& t) {
  if (next_ != nullptr) {
    if (own_) {
      pass_changed(t);
      return;
    }
    deliver(t);
  }
  cursor_ = &t.state;
}

}  // namespace gcode
