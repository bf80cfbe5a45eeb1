#include "gcode/core/layer_tracker.hpp"

#include <cmath>

#include "gcode/core/line_builder.hpp"

namespace gcode {

namespace {

// Z values are written with at most 3-4 decimals; anything closer is the same Z.
constexpr double kSameZ = 1e-4;
// While the kind of file is unknown: give up waiting for a marker after this
// many distinct extrusion heights or this much held text.
constexpr std::size_t kUndecidedLayers = 3;
constexpr std::size_t kUndecidedBytes = 8u << 20;
// Lines held after the last extrusion beyond this are released into the
// current region (a pathological file: megabytes with no extrusion).
constexpr std::size_t kTailBytes = 64u << 20;

constexpr std::size_t npos = static_cast<std::size_t>(-1);

unsigned kind_bit(MarkerKind k) { return 1u << static_cast<unsigned>(k); }

}  // namespace

struct LayerTracker::View {
  const RawLine& raw;
  const Line& line;
  const Move& move;
  const MachineState& before;
  const MachineState& after;
  int feature;
  const CommentInfo& info;
};

std::size_t LayerTracker::Held::add(const RawLine& raw) {
  std::size_t pos = arena.size();
  // One append where the ending follows the text, as read (half the cost).
  if (const std::string_view whole = raw.whole(); !whole.empty()) {
    arena.append(whole);
  } else {
    arena.append(raw.text);
    arena.append(raw.ending);
  }
  return pos;
}

// Built in place: an Item is a few hundred bytes and a third of the lines of
// a typical file are held.
void LayerTracker::keep(Held& held, const View& v) {
  std::size_t pos = held.add(v.raw);
  Item& item = held.next_slot();
  v.line.copy_onto(v.line.text, item.line);
  item.text_pos = pos;
  item.text_len = static_cast<std::uint32_t>(v.raw.text.size());
  item.ending_len = static_cast<std::uint8_t>(v.raw.ending.size());
  item.number = v.raw.number;
  item.offset = v.raw.offset;
  item.after = v.after;
  item.move = v.move;
  item.feature = v.feature;
  item.marker = v.info;
  item.marker.type = {};
}

LayerTracker::LayerTracker(LayerSink& sink, const LayerMarkers& markers) : sink_(sink), markers_(markers) {}

int LayerTracker::feature_id(std::string_view name) {
  for (std::size_t i = 0; i < features_.size(); ++i)
    if (features_[i] == name) return static_cast<int>(i);
  features_.emplace_back(name);
  return static_cast<int>(features_.size() - 1);
}

void LayerTracker::push(const RawLine& raw) {
  Line line = Line::parse(raw.text);
  if (precision_ != nullptr)
    for (const Word& w : line)
      if (w.has_value) precision_->observe(w.letter, w.decimals);
  CommentInfo info;
  if (!line.comment.empty()) {
    if (line.kind == CommandKind::None) {
      info = markers_.classify(line.comment_text());
      if (info.is_type) feature_ = feature_id(info.type);
    } else if (line.is_move()) {
      // Slic3r's verbose layer move: "G1 Z0.6 F9000 ; move to next layer (2)".
      info = markers_.classify_move(line.comment_text());
    }
  }
  previous_ = state_;
  Move move = state_.apply(line);
  View v{raw, line, move, previous_, state_, feature_, info};
  if (!track_layers_) {
    emit(v);
    return;
  }
  step(v);
}

void LayerTracker::step(const View& v) {
  if (mode_ == LayerMode::Undecided) {
    keep(pending_, v);
    if (v.info.marker != MarkerKind::None) {
      resolve_undecided(LayerMode::Markers);
    } else if (v.move.extruding) {
      double z = v.move.start[kZ];
      bool seen = false;
      for (double s : undecided_z_) seen = seen || std::fabs(s - z) <= kSameZ;
      if (!seen) undecided_z_.push_back(z);
      if (undecided_z_.size() >= kUndecidedLayers || pending_.arena.size() > kUndecidedBytes)
        resolve_undecided(LayerMode::Heuristic);
    }
    return;
  }
  if (v.move.extruding) {
    resolve_tail_for_extrusion(v);
    emit(v);
    if (mode_ == LayerMode::Heuristic || layers_ > 0) layer_z_ = v.move.end[kZ];
    return;
  }
  hold(v);
}

void LayerTracker::hold(const View& v) {
  if (tail_.empty()) before_tail_ = v.before;
  keep(tail_, v);
  if (tail_.arena.size() > kTailBytes) {
    emit_tail(0, tail_.size());
    before_tail_ = tail_.back().after;
    tail_.clear();
  }
}

void LayerTracker::resolve_undecided(LayerMode mode) {
  mode_ = mode;
  // Unmarked files often start with a purge line above the first layer
  // (Slic3r's start code draws one at Z 0.3 before a 0.2 mm first layer):
  // a first extrusion height above the next one is start code, not a layer.
  if (mode == LayerMode::Heuristic && undecided_z_.size() >= 2 && undecided_z_[0] > undecided_z_[1] + kSameZ) {
    skip_first_z_ = true;
    first_z_ = undecided_z_[0];
  }
  Held old = std::move(pending_);
  pending_.clear();
  MachineState initial;
  for (std::size_t i = 0; i < old.size(); ++i) {
    const Item& it = old[i];
    RawLine raw;
    raw.text = std::string_view(old.arena).substr(it.text_pos, it.text_len);
    raw.ending = std::string_view(old.arena).substr(it.text_pos + it.text_len, it.ending_len);
    raw.number = it.number;
    raw.offset = it.offset;
    Line line;
    it.line.copy_onto(raw.text, line);
    step(View{raw, line, it.move, i == 0 ? initial : old[i - 1].after, it.after, it.feature, it.marker});
  }
}

void LayerTracker::resolve_tail_for_extrusion(const View& extrusion) {
  if (mode_ == LayerMode::Markers) {
    resolve_markers(extrusion);
  } else {
    resolve_heuristic(extrusion);
  }
  tail_.clear();
}

const MachineState& LayerTracker::tail_state_before(std::size_t index) const {
  return index == 0 ? before_tail_ : tail_[index - 1].after;
}

void LayerTracker::begin_layer(LayerInfo info, std::size_t boundary, const View& extrusion) {
  info.index = ++layers_;
  region_ = Region::Layer;
  layer_height_ = info.height;
  // A boundary at the extrusion itself (nothing held before it) has the
  // extrusion's own before-state.
  sink_.on_layer(info, tail_.empty() ? extrusion.before : tail_state_before(boundary));
}

// The markers of one layer in the gap before an extrusion. Plain fields
// without initialisers: zeroing 64 of them on every extrusion was a quarter
// of a full pass (bench/run.sh, perf).
struct LayerTracker::MarkerGroup {
  std::size_t index;
  unsigned kinds;
  bool has_number, has_z, has_height;
  long number;
  double z, height;
};

// Markers of different kinds in one gap are one layer (PrusaSlicer profiles
// write ;LAYER_CHANGE and a custom ;LAYER:n); a repeated kind is a new one.
// Returns how many groups the held lines make (at most kMaxMarkerGroups);
// `first_z_change`: the first held line that changed Z (npos: none).
std::size_t LayerTracker::group_markers(MarkerGroup* groups, std::size_t& first_z_change) const {
  std::size_t count = 0;
  first_z_change = npos;
  const Held& items = tail_;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const CommentInfo& c = items[i].marker;
    if (first_z_change == npos && items[i].move.z_changed) first_z_change = i;
    if (c.marker != MarkerKind::None) {
      if (count == 0 || (groups[count - 1].kinds & kind_bit(c.marker)) != 0) {
        if (count == kMaxMarkerGroups) {
          // Dozens of empty layers in one gap: fold the rest into the last one.
          groups[count - 1].kinds = 0;
        } else {
          groups[count++] = MarkerGroup{i, 0, false, false, false, 0, 0, 0};
        }
      }
      MarkerGroup& g = groups[count - 1];
      g.kinds |= kind_bit(c.marker);
      if (c.has_number && !g.has_number) {
        g.has_number = true;
        g.number = c.number;
      }
    }
    if (count > 0 && c.has_z && !groups[count - 1].has_z) {
      groups[count - 1].has_z = true;
      groups[count - 1].z = c.z;
    }
    if (count > 0 && c.has_height && !groups[count - 1].has_height) {
      groups[count - 1].has_height = true;
      groups[count - 1].height = c.height;
    }
  }
  return count;
}

// The layer a group of markers starts (`last`: the group just before the
// extrusion). `continues`: it is the layer already begun (see below).
LayerInfo LayerTracker::marker_layer(const MarkerGroup& group, bool last, const View& extrusion,
                                     bool& continues) const {
  LayerInfo info;
  info.has_slicer_number = group.has_number;
  info.slicer_number = group.number;
  info.z = group.has_z ? group.z
           : last      ? extrusion.move.start[kZ]
                       : tail_[group.index].after.position[kZ];
  double previous_z = layers_ > 0 ? layer_z_ : 0;
  info.height = group.has_height ? group.height : info.z - previous_z;
  // Slic3r's verbose layer moves: a support and an object "layer" at the
  // same printed Z are one layer; in a spiral vase the move sits at the
  // previous layer's Z and the turn climbs one layer height from there.
  continues = false;
  if (group.kinds == kind_bit(MarkerKind::LayerMove) && layers_ > 0) {
    const Move& m = extrusion.move;
    bool climbs = last && m.end[kZ] > m.start[kZ] + kSameZ;
    double h = layer_height_ > kSameZ ? layer_height_ : info.z - previous_z;
    if (climbs && h > kSameZ) {
      info.z += h;
      info.height = h;
    } else if (std::fabs(info.z - previous_z) <= kSameZ) {
      continues = true;
    }
  }
  info.empty = !last;
  return info;
}

void LayerTracker::resolve_markers(const View& extrusion) {
  if (tail_.empty()) return;  // the common case: extrusion follows extrusion
  MarkerGroup groups[kMaxMarkerGroups];
  std::size_t first_z_change = npos;
  const std::size_t count = group_markers(groups, first_z_change);
  const Held& items = tail_;
  if (count == 0) {
    emit_tail(0, items.size());
    return;
  }
  std::size_t first = groups[0].index;
  if (layers_ > 0 && first_z_change < first) first = first_z_change;
  emit_tail(0, first);
  for (std::size_t g = 0; g < count; ++g) {
    bool last = g + 1 == count;
    std::size_t from = g == 0 ? first : groups[g].index;
    std::size_t to = last ? items.size() : groups[g + 1].index;
    bool continues = false;
    LayerInfo info = marker_layer(groups[g], last, extrusion, continues);
    info.first_line = from < items.size() ? items[from].number : extrusion.raw.number;
    info.offset = from < items.size() ? items[from].offset : extrusion.raw.offset;
    if (continues) {
      emit_tail(from, to);
      continue;
    }
    begin_layer(info, from, extrusion);
    layer_z_ = info.z;
    emit_tail(from, to);
  }
}

void LayerTracker::resolve_heuristic(const View& extrusion) {
  const Held& items = tail_;
  double z = extrusion.move.start[kZ];
  if (spiral_turn(extrusion)) return;
  if (layers_ > 0 && std::fabs(z - layer_z_) <= kSameZ) {
    emit_tail(0, items.size());
    return;
  }
  if (layers_ == 0 && skip_first_z_ && std::fabs(z - first_z_) <= kSameZ) {
    emit_tail(0, items.size());  // the purge: start code
    return;
  }
  // First layer: the move that went down to it. Later layers: the first Z
  // change after the previous layer's last extrusion (lift or step up).
  std::size_t boundary = items.size();
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (!items[i].move.z_changed) continue;
    boundary = i;
    if (layers_ > 0) break;
  }
  emit_tail(0, boundary);
  LayerInfo info;
  info.z = z;
  info.height = layers_ > 0 ? z - layer_z_ : z;
  info.first_line = boundary < items.size() ? items[boundary].number : extrusion.raw.number;
  info.offset = boundary < items.size() ? items[boundary].offset : extrusion.raw.offset;
  begin_layer(info, boundary, extrusion);
  emit_tail(boundary, items.size());
}

// A spiral wall (vase mode without markers) climbs inside every extruding
// move, so no move starts at a new height. Its layers are its turns: the
// first climbing extrusion starts a turn one layer height above the last
// solid layer, and each move whose end passes the turn's top starts the next.
// Returns whether the extrusion was handled here.
bool LayerTracker::spiral_turn(const View& extrusion) {
  const Move& m = extrusion.move;
  const bool climbs = m.end[kZ] > m.start[kZ] + kSameZ && m.xy_length > 0;
  if (layers_ == 0 || (!spiral_ && !climbs)) return false;
  double h = layer_height_;
  if (!spiral_) {
    if (!(h > kSameZ)) return false;
    spiral_ = true;
    turn_top_ = layer_z_;
  } else if (!climbs && std::fabs(m.start[kZ] - layer_z_) > kSameZ) {
    spiral_ = false;  // the wall ended: solid layers again
    return false;
  } else if (!(m.end[kZ] > turn_top_ + kSameZ)) {
    emit_tail(0, tail_.size());
    return true;
  }
  // The boundary: the first Z change held before this move, else the move.
  std::size_t boundary = tail_.size();
  for (std::size_t i = 0; i < tail_.size(); ++i)
    if (tail_[i].move.z_changed) {
      boundary = i;
      break;
    }
  emit_tail(0, boundary);
  turn_top_ += h;
  LayerInfo info;
  info.z = turn_top_;
  info.height = h;
  info.first_line = boundary < tail_.size() ? tail_[boundary].number : extrusion.raw.number;
  info.offset = boundary < tail_.size() ? tail_[boundary].offset : extrusion.raw.offset;
  begin_layer(info, boundary, extrusion);
  emit_tail(boundary, tail_.size());
  return true;
}

void LayerTracker::emit(const View& v) {
  sink_.on_line(TrackedLine{v.raw, v.line, v.move, v.before, v.after, region_, layers_, v.feature, LineOrigin::Input});
}

// A held line goes out once: its parsed form is moved onto the arena in
// place (a copy of it cost as much as holding it: callgrind).
void LayerTracker::emit_item(Item& item, const std::string& arena, const MachineState& before) {
  RawLine raw;
  raw.text = std::string_view(arena).substr(item.text_pos, item.text_len);
  raw.ending = std::string_view(arena).substr(item.text_pos + item.text_len, item.ending_len);
  raw.number = item.number;
  raw.offset = item.offset;
  item.line.rebase(raw.text);
  sink_.on_line(
      TrackedLine{raw, item.line, item.move, before, item.after, region_, layers_, item.feature, LineOrigin::Input});
}

void LayerTracker::emit_tail(std::size_t from, std::size_t to) {
  for (std::size_t i = from; i < to; ++i) emit_item(tail_[i], tail_.arena, tail_state_before(i));
}

void LayerTracker::finish() {
  if (finished_) return;
  finished_ = true;
  if (!track_layers_) return;
  if (mode_ == LayerMode::Undecided) resolve_undecided(LayerMode::Heuristic);
  if (layers_ > 0) {
    std::uint64_t first_line = 0, offset = 0;
    if (!tail_.empty()) {
      first_line = tail_.front().number;
      offset = tail_.front().offset;
    }
    sink_.on_end_code(first_line, offset, tail_state_before(0));
    region_ = Region::EndCode;
  }
  emit_tail(0, tail_.size());
  tail_.clear();
}

void track_all(LineReader& reader, LayerTracker& tracker) {
  RawLine raw;
  while (reader.next(raw)) tracker.push(raw);
  tracker.finish();
}

int count_layers(LineReader& reader, const LayerMarkers& markers) {
  struct Counter : LayerSink {
    void on_line(const TrackedLine&) override {}
  } counter;
  LayerTracker tracker(counter, markers);
  track_all(reader, tracker);
  return tracker.layer_count();
}

}  // namespace gcode
