#include "gcode/objects/object_excluder.hpp"

#include "gcode/transform/stream_tracker.hpp"

namespace gcode {

ObjectExcluder::ObjectExcluder(const Precision& precision, ExcludeOptions options)
    : catch_up_(precision, options.moves), options_(std::move(options)) {}

void ObjectExcluder::exclude(int index, int from_layer) {
  if (index < 0) return;
  const auto i = static_cast<std::size_t>(index);
  if (from_layer_.size() <= i) from_layer_.resize(i + 1, 0);
  from_layer_[i] = from_layer < 1 ? 1 : from_layer;
}

bool ObjectExcluder::excluded(int index) const {
  return index >= 0 && static_cast<std::size_t>(index) < from_layer_.size() && from_layer_[static_cast<std::size_t>(index)] > 0;
}

bool ObjectExcluder::leaves_out(int object, int layer) const {
  return excluded(object) && layer >= from_layer_[static_cast<std::size_t>(object)];
}

void ObjectExcluder::write(std::vector<std::string>& lines, Emitter& out) {
  if (lines.empty()) return;
  if (!noted_ && !options_.note.empty()) out.insert(options_.note);
  noted_ = true;
  for (const std::string& l : lines) out.insert(l);
  lines.clear();
}

void ObjectExcluder::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  tracker_.layer();
  out.layer(info, before);
}

void ObjectExcluder::line(const TrackedLine& t, Emitter& out) {
  const int object = blocks_ != nullptr ? blocks_->object_at(t.raw.number, block_cursor_) : tracker_.line(t.line);
  current_ = object;
  const double in_before = in_retracted_;
  in_retracted_ = RetractionTracker::after(in_retracted_, t.move);
  last_ = t.state;
  any_line_ = true;
  const bool resumed_part = start_layer_ > 0 && t.layer == 0;
  const bool in_layer = t.region == Region::Layer || resumed_part;
  if (in_layer && is_motion_line(t.move) && leaves_out(object, resumed_part ? start_layer_ : t.layer)) {
    if (!catch_up_.behind()) noted_ = false;
    catch_up_.leave(t.before, in_before);
    ++dropped_;
    if (t.move.extruding) ++dropped_extrusions_;
    return;
  }
  if (catch_up_.behind()) {
    catch_up_.before(t, in_before, lines_);
    write(lines_, out);
    out.pass(t);
    catch_up_.passed(t, in_retracted_);
    return;
  }
  out.pass(t);
}

void ObjectExcluder::finish(Emitter& out) {
  if (any_line_ && catch_up_.behind()) {
    catch_up_.all(last_, in_retracted_, lines_);
    write(lines_, out);
  }
}

}  // namespace gcode
