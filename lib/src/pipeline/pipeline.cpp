#include "gcode/pipeline/pipeline.hpp"

#include <stdexcept>

namespace gcode {

Pipeline::Pipeline(const LayerMarkers& markers, PipelineOptions options)
    : options_(options), tracker_(*this, markers), splitter_(options.block_size) {
  tracker_.set_track_layers(options.layers);
  tracker_.set_precision(&precision_);
}

Pipeline::~Pipeline() = default;

void Pipeline::add(Stage& stage) {
  if (wired_) throw std::logic_error("Pipeline::add after the first line");
  stages_.push_back(&stage);
}

// links_[k] feeds stages_[k]; each link knows whether any stage from its
// own on reads parsed lines or states, so new lines are parsed and applied
// only when someone will look.
void Pipeline::wire() {
  if (wired_) return;
  wired_ = true;
  links_.clear();
  for (std::size_t k = 0; k <= stages_.size(); ++k) links_.push_back(std::make_unique<Emitter>());
  bool parse = false, track = false;
  for (std::size_t k = stages_.size(); k-- > 0;) {
    parse = parse || stages_[k]->reads_lines() || stages_[k]->reads_state();
    track = track || stages_[k]->reads_state();
    Emitter& link = *links_[k];
    link.next_ = stages_[k];
    link.next_out_ = links_[k + 1].get();
    link.parse_ = parse;
    link.track_ = track;
  }
  for (auto& link : links_) link->cursor_ = &tracker_.state();
}

void Pipeline::on_line(const TrackedLine& line) { links_.front()->pass(line); }

void Pipeline::on_layer(const LayerInfo& layer, const MachineState& before) { links_.front()->layer(layer, before); }

void Pipeline::on_end_code(std::uint64_t first_line, std::uint64_t offset, const MachineState& before) {
  links_.front()->end_code(EndCodeInfo{first_line, offset}, before);
}

void Pipeline::drain() {
  RawLine raw;
  while (splitter_.next(raw)) tracker_.push(raw);
}

void Pipeline::feed(std::string_view bytes) {
  wire();
  splitter_.append(bytes);
  drain();
}

bool Pipeline::read_some(int fd) {
  if (finished_) return false;
  wire();
  char* room = splitter_.room();
  std::size_t n = gcode::read_some(fd, room, splitter_.room_size());
  if (n == 0) {
    finish();
    return false;
  }
  splitter_.commit(n);
  drain();
  return true;
}

void Pipeline::run(int fd) {
  while (read_some(fd)) {
  }
}

void Pipeline::run_text(std::string_view text) {
  feed(text);
  finish();
}

std::string_view Pipeline::read_header(int fd, std::size_t max_bytes) {
  std::size_t looked = 0;  // bytes of whole lines already looked at
  for (;;) {
    std::string_view pending = splitter_.pending();
    MemoryLineSplitter lines(pending.substr(looked));
    RawLine raw;
    while (lines.next(raw)) {
      if (raw.ending.empty() && !splitter_.ended()) break;  // a partial line: wait for the rest
      if (Line::parse(raw.text).is_move()) return pending;
      looked += raw.size();
    }
    if (splitter_.ended() || pending.size() >= max_bytes) return pending;
    char* room = splitter_.room();
    std::size_t n = gcode::read_some(fd, room, splitter_.room_size());
    if (n == 0) {
      splitter_.end_of_input();
    } else {
      splitter_.commit(n);
    }
  }
}

std::string_view Pipeline::read_ahead(int fd, std::size_t bytes) {
  while (!splitter_.ended() && splitter_.pending().size() < bytes) {
    char* room = splitter_.room();
    std::size_t n = gcode::read_some(fd, room, splitter_.room_size());
    if (n == 0) {
      splitter_.end_of_input();
    } else {
      splitter_.commit(n);
    }
  }
  return splitter_.pending();
}

void Pipeline::finish() {
  if (finished_) return;
  wire();
  splitter_.end_of_input();
  drain();
  finish_stages();
}

void Pipeline::finish_early() {
  if (finished_) return;
  wire();
  drain();  // whole lines still buffered go on; a partial one stays unread
  finish_stages();
}

void Pipeline::finish_stages() {
  tracker_.finish();
  finished_ = true;
  // Each stage's last words go through the stages after it, which finish later.
  const MachineState* last = &tracker_.state();
  for (std::size_t k = 0; k < stages_.size(); ++k) {
    Emitter& out = *links_[k + 1];
    if (links_[k]->own_) last = &links_[k]->state_;
    out.cursor_ = out.own_ ? &out.state_ : last;
    stages_[k]->finish(out);
  }
}

}  // namespace gcode
