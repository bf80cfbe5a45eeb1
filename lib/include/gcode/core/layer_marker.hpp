#pragma once
// Recognises the comments slicers write at layer changes
// (tests/fixtures/sources/layer-markers.md has the sources and where each
// sits relative to the layer's Z move). Numbers are the slicer's own:
//
//   CuraEngine, ideaMaker,     ;LAYER:12            (0-based, negative for raft layers)
//   Slic3r custom, MatterSlice
//   PrusaSlicer/SuperSlicer/   ;LAYER_CHANGE  then  ;Z:0.4  ;HEIGHT:0.2
//   Orca (non-Bambu printers)
//   BambuStudio/Orca           ; CHANGE_LAYER then  ; Z_HEIGHT: 0.4  ; LAYER_HEIGHT: 0.2
//   Simplify3D                 ; layer 3, Z = 0.600                      (1-based)
//   KISSlicer                  ; BEGIN_LAYER_OBJECT z=0.263 z_thickness=0.263
//   Kiri:Moto                  ;; --- layer 12 (0.200 @ 2.6) ---         (0-based)
//   Skeinforge                 (<layer> 0.4 )
//   Miracle-Grue (MakerWare)   (Slice 0, 1 Extruder)                     (0-based)
// and the ;TYPE: feature comments. Slic3r's verbose layer move
//   G1 Z0.600 F9000.000 ; move to next layer (2)                         (0-based)
// sits on a move, not on a comment-only line: classify_move() reads it.
// A user pattern (RE2) replaces the built-in markers when given; it is
// compiled once and tried on comment lines only.
#include <memory>
#include <string>
#include <string_view>

namespace re2 {
class RE2;
}

namespace gcode {

enum class MarkerKind : unsigned char {
  None,
  CuraLayer,
  LayerChange,
  ChangeLayer,
  Simplify3D,
  User,
  KISSlicer,
  KiriMoto,
  Skeinforge,
  MiracleGrue,
  LayerMove,  // Slic3r verbose "move to next layer (n)" on the layer's Z move
};

struct CommentInfo {
  MarkerKind marker = MarkerKind::None;
  bool has_number = false;
  long number = 0;           // the slicer's layer number, in the slicer's own base
  bool has_z = false;        // ;Z:, ; Z_HEIGHT:, or in the marker itself
  double z = 0;
  bool has_height = false;   // ;HEIGHT:, ; LAYER_HEIGHT:, or in the marker itself
  double height = 0;
  bool is_type = false;      // ;TYPE:name
  std::string_view type;     // the feature name, views the comment
};

class LayerMarkers {
 public:
  LayerMarkers();
  // `pattern`: an RE2 pattern matched against the comment text (after ';');
  // its first capture group, if numeric, is the slicer's layer number.
  // Throws std::invalid_argument when the pattern does not compile.
  explicit LayerMarkers(const std::string& pattern);
  ~LayerMarkers();
  LayerMarkers(LayerMarkers&&) noexcept;
  LayerMarkers& operator=(LayerMarkers&&) noexcept;

  // Classifies the comment of a comment-only line (text after the ';' or
  // inside the parentheses, blanks trimmed, as Line::comment_text gives it).
  CommentInfo classify(std::string_view comment_text) const;

  // Classifies the comment of a move line: Slic3r's (and PrusaSlicer's before
  // 2.8, SuperSlicer's) verbose layer move "move to next layer (n)" gives
  // MarkerKind::LayerMove with n, the slicer's 0-based layer number (Slic3r
  // before 1.0 wrote no number: has_number is false). The layer's Z is the
  // move's Z, except in spiral vase mode, where Slic3r writes the move at the
  // previous layer's Z and the layer climbs from there. None for anything
  // else, and always None when a user pattern replaces the built-in markers.
  CommentInfo classify_move(std::string_view comment_text) const;

  // Whether a whole line (its text, without the line ending) marks a layer
  // as LayerTracker reads it: a comment line's marker or a verbose layer move.
  bool marks_layer(std::string_view line) const;

 private:
  std::unique_ptr<re2::RE2> user_;
};

// Looks for a layer marker in text that comes block by block (a line may
// be cut between two): whether a file marks its layers, found from a part
// of it (gc-send's resume reads the printed part so).
class LayerMarkerSearch {
 public:
  explicit LayerMarkerSearch(const LayerMarkers& markers) : markers_(markers) {}
  void feed(std::string_view block);
  bool found() const { return found_; }

 private:
  static constexpr std::size_t kLongestLine = 1 << 16;  // longer: no marker (junk)
  void look(std::string_view line);

  const LayerMarkers& markers_;
  std::string cut_;  // the start of a line the last block cut
  bool found_ = false;
};

}  // namespace gcode
