#pragma once
// Complete printable G-code for a lithophane, written layer by layer.
//
// Physics in two sentences: every fill piece's speed is v = q / (width x
// layer height) and its E is width x layer height x length / filament area,
// so E per second (the extruder rate) is the same q on every piece that was
// not clamped. E is relative (M83) and written with its rounding carried from
// piece to piece. E is the planned width x layer height x the length as
// written / filament area, so width and rate are exact on every move and
// the volume matches the plan to the rounding of lengths.
//
// The text looks like Cura's, so every gc tool and slicer viewer reads it:
// ";FLAVOR:Marlin", ";LAYER_COUNT:n", ";LAYER:n" (0-based, before the layer's
// first move), ";TYPE:WALL-OUTER" / "WALL-INNER" / "FILL", then a header that
// lists every parameter. Numbers go through number.hpp (X/Y 4 decimals, Z 3,
// E 7, F 0): on hard edges pieces are cut down to a few micrometres along
// the base, where 3 decimals of X/Y would put a bead's extent across the
// band off by 20 % and more, and 6 of E a narrow piece's rate off by 1 %. Start and end code
// are built-in Marlin defaults (heat with
// M190/M109, home, a purge line in front of the part; retract, lift, heaters
// and fan off, motors off) unless the caller passes its own text.
//
// Output goes to a callback one chunk at a time (the header and start code,
// then one chunk per layer, then the end code), so memory is one layer. The
// layers are planned twice: once to total the filament for the header, once
// to write.
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/litho/lithophane.hpp"

namespace gcode::litho {

struct LithoGcodeOptions {
  double nozzle_temp = 210;       // C, PLA
  double bed_temp = 60;           // C
  std::string start_code;         // text to use instead of the built-in start (empty = built-in)
  std::string end_code;           // likewise for the end
  std::string start_name;         // where start_code came from, for the header ("" = built-in)
  std::string end_name;
  double travel_speed = 150;      // mm/s
  double retract_length = 1.0;    // mm of filament; 0 = never retract
  double retract_speed = 35;      // mm/s
  double retract_min_travel = 2;  // mm: shorter travel stays over the part and does not retract
  int fan = 255;                  // M106 S.. from the second layer; 0 = fan off
  double estimated_seconds = 0;   // > 0: written as ";TIME:" (a tool estimates on a first pass)
  std::string image_name;         // for the header
  // Throws std::invalid_argument naming the option that makes no sense.
  void validate() const;
};

struct LithoGcodeStats {
  int layers = 0;
  double volume = 0;              // mm3 written in the layers (purge line not counted)
  double filament = 0;            // mm of filament written in the layers
  std::uint64_t pieces = 0;
  std::uint64_t clamped_fast = 0; // pieces whose speed was capped at max speed
  std::uint64_t clamped_slow = 0; // pieces raised to min speed
  std::uint64_t bytes = 0;        // text written
};

using TextOut = std::function<void(std::string_view)>;

// The header's parameter lines ("name = value"), in order.
std::vector<std::string> litho_parameters(const LithophanePlanner& planner, const LithoGcodeOptions& options);

// Writes the whole program to `out`. Throws std::invalid_argument for bad options.
LithoGcodeStats write_litho_gcode(const LithophanePlanner& planner, const LithoGcodeOptions& options,
                                  const TextOut& out);

// Bounds of what the lithophane covers on the bed (for ;MINX: and friends and the purge line).
struct BedBounds {
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
};
BedBounds litho_bounds(const LithophanePlanner& planner);

}  // namespace gcode::litho
