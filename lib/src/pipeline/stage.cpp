#include "gcode/pipeline/stage.hpp"

namespace gcode {

void Emitter::deliver(const TrackedLine& t) {
  if (!next_->enabled()) {
    // A switched-off stage is skipped: its output is its input.
    next_out_->pass(t);
    return;
  }
  Emitter& out = *next_out_;
  out.cursor_ = &t.before;
  out.upstream_ = &t.before;
  out.input_line_ = t.raw.number;
  out.region_ = t.region;
  out.layer_ = t.layer;
  out.feature_ = t.feature;
  next_->line(t, out);
}

void Emitter::pass(const TrackedLine& t) {
  upstream_ = &t.state;
  if (next_ == nullptr) {
    cursor_ = &t.state;
    return;
  }
  if (!own_) {
    deliver(t);
    cursor_ = &t.state;
    return;
  }
  // The stream here was changed upstream: the line acts on this link's own
  // state, and once that equals the input's again the link follows it.
  before_ = state_;
  Move move = state_.apply(t.line);
  cursor_ = &state_;
  deliver(TrackedLine{t.raw, t.line, move, before_, state_, t.region, t.layer, t.feature, t.origin});
  if (same_machine(state_, t.state)) {
    own_ = false;
    cursor_ = &t.state;
  }
}

void Emitter::replace(const TrackedLine& t, std::string_view text) {
  upstream_ = &t.before;
  deliver_new(text, t.raw.ending, LineOrigin::Changed, &t);
  upstream_ = &t.state;
  if (own_ && same_machine(state_, t.state)) {
    own_ = false;
    cursor_ = &t.state;
  }
}

void Emitter::insert(std::string_view text) { deliver_new(text, {}, LineOrigin::Inserted, nullptr); }

void Emitter::insert_lines(std::string_view text) {
  while (!text.empty()) {
    std::size_t nl = text.find('\n');
    std::string_view one = text.substr(0, nl);
    if (!one.empty() && one.back() == '\r') one.remove_suffix(1);
    if (!one.empty()) insert(one);
    if (nl == std::string_view::npos) break;
    text.remove_prefix(nl + 1);
  }
}

void Emitter::deliver_new(std::string_view text, std::string_view ending, LineOrigin origin,
                          const TrackedLine* from) {
  if (next_ == nullptr) return;
  text_.assign(text.data(), text.size());
  RawLine raw{text_, ending, input_line_, from != nullptr ? from->raw.offset : 0};
  Line line = parse_ ? Line::parse(text_) : Line();
  if (!track_) {
    // Nobody after this reads states: the new line carries the current one.
    Move move;
    const MachineState& here = *cursor_;
    deliver(TrackedLine{raw, line, move, here, here, region_, layer_, feature_, origin});
    return;
  }
  if (!own_) {
    state_ = *cursor_;
    own_ = true;
  }
  before_ = state_;
  Move move = state_.apply(line);
  cursor_ = &state_;
  deliver(TrackedLine{raw, line, move, before_, state_, region_, layer_, feature_, origin});
}

void Emitter::layer(const LayerInfo& info, const MachineState& before) {
  upstream_ = &before;
  const MachineState& here = own_ ? state_ : before;
  cursor_ = &here;
  region_ = Region::Layer;
  layer_ = info.index;
  if (next_ == nullptr) return;
  Emitter& out = *next_out_;
  if (!next_->enabled()) {
    out.layer(info, here);
    return;
  }
  out.cursor_ = &here;
  out.upstream_ = &here;
  out.region_ = Region::Layer;
  out.layer_ = info.index;
  out.input_line_ = info.first_line;
  next_->layer(info, here, out);
}

void Emitter::end_code(const EndCodeInfo& info, const MachineState& before) {
  upstream_ = &before;
  const MachineState& here = own_ ? state_ : before;
  cursor_ = &here;
  region_ = Region::EndCode;
  if (next_ == nullptr) return;
  Emitter& out = *next_out_;
  if (!next_->enabled()) {
    out.end_code(info, here);
    return;
  }
  out.cursor_ = &here;
  out.upstream_ = &here;
  out.region_ = Region::EndCode;
  out.layer_ = layer_;
  out.input_line_ = info.first_line;
  next_->end_code(info, here, out);
}

}  // namespace gcode
