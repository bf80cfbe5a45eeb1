#pragma once
// gc-swap-layer's edits of a print, as a SplicePlan (splice.hpp): replace
// layers by layers of another file, leave layers out, print a layer again,
// insert a block after a layer. Several edits in one run apply in layer
// order while the print streams by; Z shifts add up.
//
//   --layer RANGE --with FILE[:LAYERS]   each layer of RANGE by FILE's layer at
//                                        the same Z (or the listed ones, in
//                                        order), placed at the replaced Z
//   --skip RANGE [--keep-z]              left out; later layers come down by
//                                        the removed thickness, or keep their
//                                        Z and the next layer's extrusion is
//                                        scaled by (h + skipped) / h (the
//                                        paper's "expressive surface")
//   --repeat LAYER[xN]                   printed N more times, later layers up
//   --insert-after LAYER --file FILE     FILE's layers on top of LAYER, later
//                                        layers up by FILE's height
//
// Layers are numbered as gc-layers numbers them (RANGE as everywhere: 5,
// 5-9, 5-, -3, 5,7,9-12); '@' gives heights instead: @1.2 is the layer at Z
// 1.2, @1:2.4 the layers from Z 1 to 2.4.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/layer_range.hpp"
#include "gcode/transform/layer_index.hpp"
#include "gcode/transform/splice.hpp"

namespace gcode {

// Layers by number (a LayerRange) or by height ('@' then Z or Z1:Z2).
class LayerPick {
 public:
  // Throws std::invalid_argument naming the bad part.
  static LayerPick parse(std::string_view text);
  bool contains(const LayerInfo& layer, int total) const;
  bool needs_total() const { return range_ && range_->needs_total(); }
  // The highest layer number named (0 for heights and open ends).
  int highest_named() const { return range_ ? range_->highest_named() : 0; }
  bool by_height() const { return !range_.has_value(); }
  const std::string& text() const { return text_; }

 private:
  std::optional<LayerRange> range_;
  ZRange z_;
  std::string text_;
};

// "12" or "12x3" (@Z too): a layer and how many more times to print it.
struct RepeatText {
  LayerPick layer;
  int times = 1;
  static RepeatText parse(std::string_view text);
};

// "b.gcode" or "b.gcode:5-9" (the part after the last ':' when it is a range).
struct FileLayersText {
  std::string file;
  std::optional<LayerPick> layers;
  static FileLayersText parse(std::string_view text);
};

// The edits as given on the command line.
struct LayerEditsText {
  std::vector<std::string> replace;       // --layer RANGE
  std::vector<std::string> with;          // --with FILE[:LAYERS], one per --layer
  std::string skip;                       // --skip RANGE
  bool keep_z = false;                    // --keep-z
  std::vector<std::string> repeat;        // --repeat LAYER[xN]
  std::vector<std::string> insert_after;  // --insert-after LAYER
  std::vector<std::string> insert_file;   // --file FILE, one per --insert-after

  bool any() const { return !replace.empty() || !skip.empty() || !repeat.empty() || !insert_after.empty(); }
  bool needs_total() const;
  // The other files named (--with, --file), without their :LAYERS.
  std::vector<std::string> files() const;
  // Throws std::invalid_argument for what makes no sense whatever the input:
  // unpaired options, bad ranges, a layer both left out and replaced.
  void validate() const;
};

// An open second file: its descriptor and its layer index.
struct SpliceFile {
  std::string name;
  int fd = -1;
  LayerIndex* index = nullptr;
};

class LayerEditPlan : public SplicePlan {
 public:
  // `main_fd`: the main input (a regular file: --repeat reads its layers
  // again; -1 when nothing is repeated). `files`: the --with and --file files
  // by name. `total`: the input's layer count when a range counts from the
  // end, else 0. `z_decimals`: the input's Z precision for heights.
  LayerEditPlan(const LayerEditsText& text, int main_fd, const LayerMarkers& markers, std::vector<SpliceFile> files,
                int total, int z_decimals, Diagnostics* diag, std::string note_prefix);

  LayerAction at_layer(const LayerInfo& info, const SpliceContext& context) override;
  LayerAction at_end_code(const SpliceContext& context) override;

  // After the run: throws std::runtime_error for an edit the input could not
  // meet (a layer beyond it, a height none of its layers has).
  void verify() const;
  // What was done, one line per edit ("layer 7 (Z 1.4) replaced by layer 7 of b.gcode").
  const std::vector<std::string>& report() const { return report_; }

 private:
  struct Replace {
    LayerPick layers;
    SpliceFile file;
    std::vector<int> file_layers;  // explicit, in order; empty: by Z
    std::size_t used = 0;
    bool matched = false;
  };
  struct Repeat {
    LayerPick layer;
    int times;
    bool matched = false;
  };
  struct Insert {
    LayerPick after;
    SpliceFile file;
    bool matched = false;
  };

  void after_layer(const SpliceContext& context, LayerAction& action);
  // at_layer's steps.
  void skip_layer(const LayerInfo& info, LayerAction& action);
  double fill_scale(const LayerInfo& info);
  int replacement_of(Replace& r, const LayerInfo& info);
  void replace_layer(Replace& r, const LayerInfo& info, const SpliceContext& context, double scale,
                     LayerAction& action);
  void check_placement(const SpliceFile& file, int below, const SpliceContext& context);
  Fixed z_of(double z) const;

  int main_fd_;
  const LayerMarkers& markers_;
  std::optional<LayerPick> skip_;
  bool keep_z_;
  std::vector<Replace> replace_;
  std::vector<Repeat> repeat_;
  std::vector<Insert> insert_;
  int total_;
  int z_decimals_;
  Diagnostics* diag_;
  std::string note_;
  bool skip_matched_ = false;
  int layers_seen_ = 0;
  double fill_ = 0;           // --keep-z: thickness left out since the last printed layer
  int fill_first_ = 0, fill_last_ = 0;
  std::vector<std::string> checked_;  // files whose placement was checked
  std::vector<std::string> report_;
};

}  // namespace gcode
