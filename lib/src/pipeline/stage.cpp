#include "gcode/pipeline/stage.hpp"

namespace gcode {

void Emitter::pass_changed(const TrackedLine& t) {
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

void Emitter::dropped(const TrackedLine& t) {
  // A later stage must not see the state of a line that never reached it.
  if (same_machine(t.before, t.state)) return;
  state_ = t.before;
  own_ = true;
  cursor_ = &state_;
}

void Emitter::replace(const TrackedLine& t, std::string_view text) {
  deliver_new(text, t.raw.ending, LineOrigin::Changed, &t);
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
  RawLine raw{text_, ending, input_line(), from != nullptr ? from->raw.offset : 0};
  // Not Line(): value-initialised, it clears all 24 word slots (896 bytes,
  // a rep stos for every new line); an empty parse sets only the fields.
  Line line = Line::parse(parse_ ? std::string_view(text_) : std::string_view());
  const Region region = this->region();
  const int layer = layer_index(), feature = this->feature();
  if (!track_) {
    // Nobody after this reads states: the new line carries the current one.
    Move move;
    const MachineState& here = *cursor_;
    deliver(TrackedLine{raw, line, move, here, here, region, layer, feature, origin});
    return;
  }
  if (!own_) {
    state_ = *cursor_;
    own_ = true;
  }
  before_ = state_;
  Move move = state_.apply(line);
  cursor_ = &state_;
  deliver(TrackedLine{raw, line, move, before_, state_, region, layer, feature, origin});
}

void Emitter::layer(const LayerInfo& info, const MachineState& before) {
  if (line_ != nullptr) feature_ = line_->feature;
  line_ = nullptr;
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
  // Lines the next stage adds before it passes the event on end the
  // previous layer: its own out.layer() moves its context to the new one.
  out.line_ = nullptr;
  out.cursor_ = &here;
  out.input_line_ = info.first_line;
  next_->layer(info, here, out);
}

void Emitter::end_code(const EndCodeInfo& info, const MachineState& before) {
  if (line_ != nullptr) feature_ = line_->feature;
  line_ = nullptr;
  const MachineState& here = own_ ? state_ : before;
  cursor_ = &here;
  region_ = Region::EndCode;
  if (next_ == nullptr) return;
  Emitter& out = *next_out_;
  if (!next_->enabled()) {
    out.end_code(info, here);
    return;
  }
  out.line_ = nullptr;
  out.cursor_ = &here;
  out.input_line_ = info.first_line;
  next_->end_code(info, here, out);
}

}  // namespace gcode
