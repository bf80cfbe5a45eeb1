#pragma once
// The pipeline stage of gc-litho --texture: every extruding piece whose
// middle falls on the picture runs at the speed of its pixel, with its E
// scaled by old speed / new speed so E per second stays what the slicer
// planned (texture.hpp says why).
//
// The stage does not cut moves: it comes after the Subdivider (gc-subdivide's
// stage, at --max = the texture's resolution, travel left whole), so the
// path is exactly gc-subdivide's and each piece is at most one step long.
// What it keeps:
//   - F is modal: F is written only where the speed changes, and before the
//     first move after a textured run that has no F of its own a
//     "G1 F<input's F>" line puts the input's speed back (the move itself,
//     and a move with its own F, stay as they are);
//   - relative E (M83): each piece's E is scaled, the rounding carried;
//   - absolute E (M82): the scaled E runs ahead of the input's, so before
//     the next line that uses E (a retraction, an unchanged extrusion,
//     M82/M83) a "G92 E<input's E>" puts the two back in step: everything
//     else stays byte for byte. A G92 of the input resets the difference too;
//   - only extruding XY moves in the selection (--layers, --z-range,
//     --types) at or above skip_z change; travel, retractions, Z moves,
//     numbered lines and inches (G20) pass as they are.
// A header comment with the parameters goes before the first command.
#include <cstdint>
#include <string>
#include <vector>

#include "gcode/core/fixed.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/litho/texture.hpp"
#include "gcode/pipeline/selection.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gcode::litho {

struct TextureStats {
  std::uint64_t extrusions = 0;   // extruding moves the stage saw in the selection
  std::uint64_t textured = 0;     // pieces that got their pixel's speed
  std::uint64_t outside = 0;      // extruding moves in the selection off the picture (left as they were)
  std::uint64_t speed_words = 0;  // F words written for a new speed
  std::uint64_t restores = 0;     // F words written to put the input's speed back
  std::uint64_t resyncs = 0;      // G92 E lines inserted (absolute E)
  int layers = 0;                 // layers with extrusions the stage saw
  int spiral_layers = 0;          // of those, layers whose extrusions climb (a spiral wall)
  double slowest = 0;             // mm/s of the textured pieces
  double fastest = 0;
};

class TextureStage : public Stage {
 public:
  // `projection`, `image` and `speeds` must outlive the stage. `precision`:
  // the input's decimals per letter (Pipeline::precision). `selection` may
  // be null (every layer and feature). `header`: comment lines (without ';')
  // written before the first command.
  TextureStage(const TextureProjection& projection, const GreyImage& image, const SpeedMapping& speeds, double skip_z,
               const Precision& precision, LayerSelection* selection, std::vector<std::string> header);

  void line(const TrackedLine& t, Emitter& out) override;
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) override;
  void finish(Emitter& out) override;

  const TextureStats& stats() const { return stats_; }

 private:
  bool texture(const TrackedLine& t, Emitter& out);
  void resync(const TrackedLine& t, Emitter& out);
  void write_header(Emitter& out);
  void close_layer();

  const TextureProjection& projection_;
  const GreyImage& image_;
  const SpeedMapping& speeds_;
  double skip_z_;
  const Precision& precision_;
  LayerSelection* selection_;
  std::vector<std::string> header_;
  bool header_written_ = false;
  double out_feed_ = -1;     // mm/min the output runs at now (-1: as the input)
  Fixed e_offset_;           // absolute E: output E minus input E
  double e_carry_ = 0;       // relative E: rounding not yet written
  double layer_low_ = 0;     // Z range of the current layer's extrusions
  double layer_high_ = -1;
  TextureStats stats_;
  LineBuilder builder_;
  std::vector<TexturePiece> pieces_;
};

// The header's lines for a textured file ("gc-litho --texture", then one
// "name = value" a parameter).
std::vector<std::string> texture_parameters(const std::string& image_name, const GreyImage& image,
                                            const TextureProjection& projection, const SpeedMapping& speeds,
                                            double resolution, double skip_z, const std::string& types);

}  // namespace gcode::litho
