#pragma once
// What a splice prints: a block of G-code, bytes [begin, end) of a file (one
// or more layers, or everything from a layer on, end code included), how the
// machine stands at `begin`, a Z shift and an extrusion factor; from a
// LayerIndex (layer_index_block) or from a layer of the main stream itself
// (--repeat). And whether another file's blocks fit the input: the printer
// it was sliced for and where its part lies.
#include <cstdint>
#include <string>

#include "gcode/core/fixed.hpp"
#include "gcode/core/geometry.hpp"
#include "gcode/core/layer_marker.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/print_area.hpp"
#include "gcode/transform/layer_index.hpp"
#include "gcode/transform/stream_tracker.hpp"

namespace gcode {

struct SpliceBlock {
  int fd = -1;                       // read with pread; not owned
  std::string name;                  // for messages
  const LayerMarkers* markers = nullptr;
  std::uint64_t begin = 0;           // the first byte (a layer's start)
  std::uint64_t end = 0;             // one past the last byte
  bool through_end = false;          // the block ends with the file's end code (its event is passed on)
  std::uint64_t first_line = 1;      // the file's line number at `begin` (messages)
  LayerInfo first_layer;             // the layer at `begin`
  StreamPoint start;                 // how the file stands at `begin` (layer_z: first_layer.z)
  Fixed z_shift;                     // added to every absolute Z of the block
  double extrusion_scale = 1;        // factor for its extruding moves
  std::string note;                  // the seam's comment
  // The printed side stands exactly where this block starts (the block
  // printed last ended at `begin` of the same file, with the same shift):
  // no seam, the lines go on. Set by SpliceStage.
  bool continues = false;
};

// What differs between the printer a file was sliced for and the input's
// (the bed), as a warning text; empty when nothing is known to differ.
std::string printer_difference(const PrintArea& input, const PrintArea& other, const std::string& other_name);

// Whether another slicing of the part lies where the input prints: the
// centres of the two XY extents (what was printed, what the other file
// prints below the join) more than 2 mm apart means another printer or
// placement. Returns the error text, empty when they agree or either extent
// is empty.
std::string placement_difference(const Box2& printed, const Box2& theirs, const std::string& their_name);

// Layers first..last of an indexed file (through_end: first to the end of
// the file, end code included). The index must have reached them.
SpliceBlock layer_index_block(const LayerIndex& index, int first, int last, bool through_end = false);

}  // namespace gcode
