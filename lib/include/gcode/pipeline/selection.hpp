#pragma once
// Where a transform applies, as every tool takes it: --layers RANGE,
// --z-range Z1:Z2 and --types LIST (slicer ;TYPE: names, case-insensitive,
// any slicer's spelling: WALL-OUTER also selects PrusaSlicer's "External
// perimeter", see feature.hpp). Given criteria intersect; none given selects
// everything, start and end code included.
//
// A stage keeps one and tells it about layers as they come (enter_layer);
// then selects(line) says whether a line lies where the user asked.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/layer_range.hpp"
#include "gcode/core/layer_tracker.hpp"

namespace gcode {

struct SelectionText {
  std::string layers;   // --layers
  std::string z_range;  // --z-range
  std::string types;    // --types, comma-separated
};

class LayerSelection {
 public:
  LayerSelection() = default;
  // Throws std::invalid_argument naming the option that does not parse.
  static LayerSelection parse(const SelectionText& text);

  bool any() const { return by_layer() || !types_.empty(); }
  bool by_layer() const { return range_.has_value() || z_range_.has_value(); }
  // A range counted from the end ("-3") needs the file's layer count first.
  bool needs_total() const { return range_ && range_->needs_total(); }
  void set_total(int layers) { total_ = layers; }
  // Resolves ;TYPE: names to the file's feature ids.
  void bind(const LayerTracker& tracker) { tracker_ = &tracker; }

  // Whether a layer is chosen by --layers and --z-range.
  bool layer_selected(const LayerInfo& info) const;
  // Call at each layer start, before its lines.
  void enter_layer(const LayerInfo& info);
  // Call at the start of the end code.
  void enter_end_code() { in_selected_layer_ = false; }
  // Whether a line lies in the selection (layer, height and feature).
  bool selects(const TrackedLine& t);
  bool feature_selected(int feature);

  int layers_selected() const { return layers_selected_; }
  const std::vector<std::string>& types() const { return types_; }
  // The --types names that matched no feature of the input read so far.
  std::vector<std::string> unmatched_types() const;
  const std::optional<LayerRange>& range() const { return range_; }

 private:
  std::optional<LayerRange> range_;
  std::optional<ZRange> z_range_;
  std::vector<std::string> types_;
  const LayerTracker* tracker_ = nullptr;
  int total_ = 0;
  bool in_selected_layer_ = false;
  int layers_selected_ = 0;
  std::vector<signed char> by_feature_;  // feature id -> -1 unknown, 0 no, 1 yes
};

// Splits "a,b,,c" into its non-empty items (spaces around items trimmed).
std::vector<std::string> split_list(std::string_view text);

}  // namespace gcode
