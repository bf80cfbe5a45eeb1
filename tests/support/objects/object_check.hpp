#pragma once
// The independent checker for gc-objects --exclude. It shares no code with
// the tool or the library: its own small G-code reader (G0-G3 end points, G28,
// G90/G91, M82/M83, G92, G10/G11, G20/G21) and its own reading of the
// object labels of every slicer. It replays the input and the output and
// proves:
//   (a) the output's extrusions are exactly the input's extrusions of the
//       objects kept (and those outside every object), in the same order,
//       each from the same start point to the same end point (X, Y, Z) with
//       the same filament;
//   (b) before each of them, the filament is retracted exactly as deep as
//       in the input (E moves and wipes; firmware retraction as in the input);
//   (c) nothing of a left-out object is extruded (from layer N on, with
//       --from-layer: layers counted as the rising Z of extrusions);
//   (d) at the end the position, the retraction and firmware retraction
//       are as the input leaves them.
#include <string>
#include <string_view>
#include <vector>

namespace gctest {

struct ObjectCheck {
  bool ok = true;
  std::string message;      // the first difference, where not ok
  std::size_t kept = 0;     // extrusions checked in the output
  std::size_t left_out = 0; // extrusions of the left-out objects in the input
};

// `left_out`: the left-out objects, each by its label's number where the
// label has one (PrusaSlicer's "id.copy" for copies past the first), else
// by its name (Cura's meshes, Klipper's NAME=); in a file without labels,
// "box:X0,Y0,X1,Y1": the extrusions with both ends in that box.
// `from_layer`: 0 (everywhere) or the first layer left out.
ObjectCheck check_objects_left_out(std::string_view input, std::string_view output, const std::vector<std::string>& left_out,
                                   int from_layer = 0);

}  // namespace gctest
