#pragma once
// Pictures of layers seen from above, as SVG.
//
// A LayerDrawer (a report stage) collects the paths of the selected layers
// while the file streams: extrusions by feature (;TYPE:) with their
// width (;WIDTH: when the slicer writes it, else filament volume / (length x
// layer height)), travel, retraction points, and the extrusions of the layer
// below each selected one. Consecutive segments of the same style are merged
// into one polyline, which keeps the files small. Memory: the selected layers
// plus the one being read.
//
// layer_svg() draws one layer; layer_sheet_svg() puts several in a grid with
// one legend. The bed outline is drawn when the caller knows it
// (print_area.hpp reads it from the file).
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/geometry.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gcode {

struct DrawnPath {
  bool travel = false;
  int feature = -1;     // LayerTracker feature id, -1 for none
  float width = 0;      // mm (extrusions)
  std::vector<float> xy;  // x0 y0 x1 y1 ...
};

struct LayerDrawing {
  int layer = 0;
  double z = 0;
  double height = 0;
  double seconds = -1;           // the layer's print time, < 0 when unknown
  std::vector<DrawnPath> paths;  // in print order
  std::vector<DrawnPath> below;  // extrusions of the layer below
  std::vector<float> retractions;  // x y pairs
};

class LayerDrawer : public Stage {
 public:
  // `selected(layer)` says which layers to keep.
  explicit LayerDrawer(std::function<bool(int)> selected, double filament_diameter = 1.75);

  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void line(const TrackedLine& t, Emitter& out) override;
  void finish(Emitter& out) override;

  std::vector<LayerDrawing>& drawings() { return done_; }

 private:
  void add_segment(bool travel, int feature, float width, double x0, double y0, double x1, double y1);
  void close_layer();

  std::function<bool(int)> selected_;
  double filament_area_;
  LayerDrawing current_;
  bool current_selected_ = false;
  std::vector<DrawnPath> previous_;  // extrusions of the layer before the current one
  std::vector<LayerDrawing> done_;
  double width_comment_ = 0;  // the last ;WIDTH:
  bool in_layer_ = false;
};

struct SvgOptions {
  bool travel = true;        // dashed travel lines
  bool below = true;         // the layer below in grey
  bool retractions = true;   // retraction points
  double size_px = 800;      // the longer side of one layer's picture
  Polygon bed;               // outline, drawn where it falls in the picture; empty = unknown
  std::vector<std::string> feature_names;  // by feature id
};

std::string layer_svg(const LayerDrawing& drawing, const SvgOptions& options);
// `columns` 0 = about square.
std::string layer_sheet_svg(const std::vector<LayerDrawing>& drawings, const SvgOptions& options, int columns = 0);

// "layer-{}.svg", "layer-{layer}.svg" or "layer-%d.svg" with the layer number (placeholders.hpp); a path without a
// placeholder is returned as it is.
std::string expand_layer_pattern(std::string_view pattern, int layer);
bool has_layer_placeholder(std::string_view pattern);

// --svg and --svg-sheet: the drawings, each given its layer's time from
// `layer_seconds` ([i] = layer i + 1, when known), as one sheet (`sheet`) or
// one picture a layer, each handed to `write` with its path: `out`, or with
// several layers `out` expanded by layer (a pattern such as layer-{}.svg).
// Throws std::runtime_error when no layer was drawn, or when several
// pictures would go to one path.
void write_layer_pictures(std::vector<LayerDrawing>& drawings, const SvgOptions& options,
                          const std::vector<double>& layer_seconds, bool sheet, const std::string& out,
                          const std::function<void(const std::string& path, const std::string& svg)>& write);

// A fixed colour per feature name (slicers' names, case-insensitive), as "#rrggbb".
std::string feature_color(std::string_view name);

// `s` as XML text (&, <, >, " escaped; control characters left out).
void append_xml_text(std::string& out, std::string_view s);

}  // namespace gcode
