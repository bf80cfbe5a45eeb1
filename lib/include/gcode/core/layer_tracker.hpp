#pragma once
// Splits a G-code stream into start code, layers and end code, as it streams.
//
// The model (background.md §1): start code before the first layer, then the
// layers, then end code = everything after the last extruding move of the last
// layer. Layer starts come from slicer markers (layer_marker.hpp) or, in files
// without any, from the Z heuristic: a layer starts with the first extruding
// move that begins at a Z other than the current layer's. Z-hops come back
// down before extruding, and vase-mode Z rises inside extruding moves, so
// neither starts a layer.
//
// Where exactly does a layer begin? Between the last extrusion of one layer
// and the first of the next lie retracts, lifts, travel and comments. The
// boundary is put at the earlier of the slicer's marker and the first move
// that changes Z after the last extrusion: CuraEngine writes the move to the
// next layer's Z *before* its ;LAYER:n marker, and that move belongs to the
// new layer. So the lines after each extrusion are held back until the next
// extrusion (or the end) decides where they go; memory is bounded by that gap,
// not by the file.
//
// Until the first marker or a few layers' worth of extrusion show which kind
// of file this is, lines are held too: a purge line before the first marker is
// start code, while in an unmarked file it is a layer of its own.
#include <cstdint>
#include <string>
#include <vector>

#include "gcode/core/layer_marker.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/machine_state.hpp"

namespace gcode {

enum class Region : std::uint8_t { StartCode, Layer, EndCode };

struct LayerInfo {
  int index = 0;               // 1 = first printed layer
  bool has_slicer_number = false;
  long slicer_number = 0;      // the slicer's own number (Cura's ;LAYER:n)
  double z = 0;                // the layer's Z (marker ;Z: or where extrusion starts)
  double height = 0;           // marker ;HEIGHT: or Z minus the previous layer's Z
  std::uint64_t first_line = 0;  // line number where the layer begins
  std::uint64_t offset = 0;      // byte offset where the layer begins
  bool empty = false;          // a marker with no extrusion before the next one
};

// Where a line's text comes from, which decides how it is written back.
enum class LineOrigin : std::uint8_t {
  Input,     // the input's own line: written from its raw bytes
  Changed,   // a stage rewrote an input line: new text, the input line's own ending
  Inserted,  // a stage added it: written with the input's line ending
};

// Everything known about one line when it reaches a sink or a stage. The
// references and views are valid during the call only.
struct TrackedLine {
  const RawLine& raw;          // text and ending; number = the input line (for a
                               // line a stage made: the input line it came with)
  const Line& line;
  const Move& move;
  const MachineState& before;  // before the line
  const MachineState& state;   // after the line
  Region region;
  int layer;                   // current layer index; 0 in the start code
  int feature;                 // index into LayerTracker::feature_name, -1 if none yet
  LineOrigin origin = LineOrigin::Input;
};

class LayerSink {
 public:
  virtual ~LayerSink() = default;
  // Just before the first line of a layer; `before` is the state at that point.
  virtual void on_layer(const LayerInfo& layer, const MachineState& before) {
    (void)layer;
    (void)before;
  }
  // Just before the first line of the end code (called even if it is empty).
  virtual void on_end_code(std::uint64_t first_line, std::uint64_t offset, const MachineState& before) {
    (void)first_line;
    (void)offset;
    (void)before;
  }
  virtual void on_line(const TrackedLine& line) = 0;
};

// How the layers of a file were found: the slicer's markers, the heights of
// the extrusions, or the turns of a spiral wall (a vase printed without
// markers: one layer per layer height of climb).
enum class LayerMode : std::uint8_t { Undecided, Markers, Heuristic, Spiral };

class Precision;

class LayerTracker {
 public:
  LayerTracker(LayerSink& sink, const LayerMarkers& markers);

  // Without layers every line goes to the sink at once, in the start code
  // (for tools that need no layer: nothing is held back).
  void set_track_layers(bool on) { track_layers_ = on; }
  // The E mode the file relies on without saying it (e_mode.hpp): set before
  // the first line; the file's own M82/M83 still wins where it has one.
  void set_e_mode(bool relative) {
    state_.relative_e = relative;
    state_.e_follows_g90 = false;
  }
  // A stream that continues another one (gc-send's live swap): the machine
  // stands in `state` before the first line. Before the first line.
  void start_from(const MachineState& state) {
    state_ = state;
    previous_ = state;
    before_tail_ = state;
  }
  // A stream that continues a print inside its layers (gc-send's resume):
  // the kind of file is known from what was printed, so no line is held
  // back to find it out (held, the lines up to the next marker reached the
  // sink in one batch). Before the first line.
  void decide_mode(LayerMode mode) { mode_ = mode; }
  // Records the decimals the input uses per letter (see Precision).
  void set_precision(Precision* precision) { precision_ = precision; }

  // Feeds one line. It reaches the sink now or later, always in input order.
  void push(const RawLine& raw);
  // End of input: releases every held line.
  void finish();

  LayerMode mode() const { return mode_ == LayerMode::Heuristic && spiral_ ? LayerMode::Spiral : mode_; }
  int layer_count() const { return layers_; }
  // The state after the last line pushed (not necessarily emitted yet).
  const MachineState& state() const { return state_; }
  bool finished() const { return finished_; }
  const std::string& feature_name(int id) const { return features_[static_cast<std::size_t>(id)]; }
  int feature_count() const { return static_cast<int>(features_.size()); }

 private:
  struct Item {
    Line line;                 // parsed once; its views are moved onto the arena when emitted
    std::size_t text_pos = 0;
    std::uint32_t text_len = 0;
    std::uint8_t ending_len = 0;
    std::uint64_t number = 0;
    std::uint64_t offset = 0;
    MachineState after;
    Move move;
    int feature = -1;
    CommentInfo marker;  // only marker / z / height fields are kept
  };
  // Held lines. Slots are reused, not rebuilt: an Item is large (the parsed
  // line, the state after it) and a third of a typical file passes through.
  struct Held {
    std::vector<Item> slots;
    std::size_t count = 0;
    std::string arena;
    void clear() {
      count = 0;
      arena.clear();
    }
    std::size_t size() const { return count; }
    bool empty() const { return count == 0; }
    Item& operator[](std::size_t i) { return slots[i]; }
    const Item& operator[](std::size_t i) const { return slots[i]; }
    const Item& front() const { return slots[0]; }
    const Item& back() const { return slots[count - 1]; }
    Item& next_slot() {
      if (count == slots.size()) slots.emplace_back();
      return slots[count++];
    }
    std::size_t add(const RawLine& raw);
  };
  struct View;  // an item and where its text lives

  static void keep(Held& held, const View& v);
  void step(const View& v);
  void hold(const View& v);
  void resolve_undecided(LayerMode mode);
  void resolve_tail_for_extrusion(const View& extrusion);
  void resolve_markers(const View& extrusion);
  struct MarkerGroup;  // the markers of one layer in a gap (layer_tracker.cpp)
  static constexpr std::size_t kMaxMarkerGroups = 64;
  std::size_t group_markers(MarkerGroup* groups, std::size_t& first_z_change) const;
  LayerInfo marker_layer(const MarkerGroup& group, bool last, const View& extrusion, bool& continues) const;
  void resolve_heuristic(const View& extrusion);
  void emit_tail(std::size_t from, std::size_t to);
  void emit(const View& v);
  void emit_item(Item& item, const std::string& arena, const MachineState& before);
  void begin_layer(LayerInfo info, std::size_t boundary, const View& extrusion);
  bool spiral_turn(const View& extrusion);
  const MachineState& tail_state_before(std::size_t index) const;
  int feature_id(std::string_view name);

  LayerSink& sink_;
  const LayerMarkers& markers_;
  LayerMode mode_ = LayerMode::Undecided;
  MachineState state_;
  MachineState previous_;     // before the line being pushed
  MachineState before_tail_;  // before the first held line
  Held pending_;   // everything, while the mode is undecided
  Held tail_;      // lines since the last extrusion
  std::vector<double> undecided_z_;  // distinct extrusion Z seen while undecided
  std::vector<std::string> features_;
  int feature_ = -1;
  int layers_ = 0;
  Region region_ = Region::StartCode;
  double layer_z_ = 0;
  double layer_height_ = 0;   // of the current layer
  bool skip_first_z_ = false; // unmarked: the first extrusion height was a purge above layer 1
  double first_z_ = 0;
  bool spiral_ = false;       // extrusions climb: a spiral wall, one layer per turn
  double turn_top_ = 0;       // the Z at which the current turn ends
  bool finished_ = false;
  bool track_layers_ = true;
  Precision* precision_ = nullptr;
};

// Pushes every line of `reader` through `tracker`, then finishes it.
void track_all(LineReader& reader, LayerTracker& tracker);
// Reads `reader` to the end and returns how many layers it holds (for
// selections counted from the end, such as "the last 3 layers").
int count_layers(LineReader& reader, const LayerMarkers& markers);

}  // namespace gcode
