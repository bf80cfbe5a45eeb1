#pragma once
// Leaves objects out of a print: a stage that drops every motion of the
// switched-off objects' blocks and keeps everything else, lines of the
// other objects byte for byte.
//
// Inside a left-out block only motion is dropped (G0-G3, firmware
// retraction); temperatures, fans, tools, modes, G92, comments and labels
// stay where they are, so whatever the rest of the print relies on from
// them is set as in the input. Where the output left the input's path,
// StreamCatchUp (catch_up.hpp) writes, before each further line, only what
// that line depends on: the retraction depth and firmware retraction, the E
// coordinate, the position, the feed rate; the travel goes straight to the
// next kept object. At the end of the input the printer is where the input
// leaves it.
//
// An object can be switched off at any line (gc-send's `cancel object`):
// exclude() takes effect from the next line the stage sees, also in the
// middle of that object's block; from_layer leaves it in up to that layer.
#include <cstdint>
#include <string>
#include <vector>

#include "gcode/objects/catch_up.hpp"
#include "gcode/objects/footprints.hpp"
#include "gcode/objects/object_tracker.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gcode {

struct ExcludeOptions {
  CatchUpMoves moves;
  std::string note;  // a comment line written where a left-out stretch ends ("" for none)
};

class ObjectExcluder : public Stage {
 public:
  explicit ObjectExcluder(const Precision& precision, ExcludeOptions options = {});
  // Object `index` (ObjectTracker's numbering, the same as ObjectTable's)
  // is left out from layer `from_layer` on (0 or 1: from now).
  void exclude(int index, int from_layer = 0);
  // Objects found from footprints (footprints.hpp): the object of each line
  // from its blocks, not from labels. Before the first line.
  void use_blocks(const ObjectBlocks* blocks) { blocks_ = blocks; }
  bool excluded(int index) const;
  // The object the last line belonged to (-1 for none), and the tracker
  // (names registered so far: a live stream may name objects only as it goes).
  int current() const { return current_; }
  const ObjectTracker& tracker() const { return tracker_; }
  // A stream that goes on from lines read elsewhere (gc-send --resume reads
  // the labels of the printed part): the names, their numbering and the
  // object the stream stands in, as `before` left them.
  void continue_from(const ObjectTracker& before) { tracker_ = before; }
  // A stream that begins inside layer `layer` (gc-send --resume): its lines
  // before its first layer are of that layer, not start code, and may be
  // left out. The lines go on as they came.
  void start_inside_layer(int layer) { start_layer_ = layer; }
  // Motion lines left out so far, and extrusions among them.
  std::uint64_t dropped_lines() const { return dropped_; }
  std::uint64_t dropped_extrusions() const { return dropped_extrusions_; }

  void line(const TrackedLine& t, Emitter& out) override;
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void finish(Emitter& out) override;

 private:
  bool leaves_out(int object, int layer) const;
  void write(std::vector<std::string>& lines, Emitter& out);
  ObjectTracker tracker_;
  const ObjectBlocks* blocks_ = nullptr;
  std::size_t block_cursor_ = 0;
  int current_ = -1;
  StreamCatchUp catch_up_;
  ExcludeOptions options_;
  std::vector<int> from_layer_;  // per object: 0 kept, else the first layer left out
  int start_layer_ = 0;          // see start_inside_layer
  double in_retracted_ = 0;      // the input's retraction (RetractionTracker)
  MachineState last_;            // the input's state after the last line
  bool any_line_ = false;
  bool noted_ = false;
  std::uint64_t dropped_ = 0;
  std::uint64_t dropped_extrusions_ = 0;
  std::vector<std::string> lines_;
};

}  // namespace gcode
