#pragma once
// Recognises the comments slicers write at layer changes.
//
//   CuraEngine, Slic3r custom  ;LAYER:12            (number, 0-based, negative for raft)
//   PrusaSlicer/Slic3r/Orca    ;LAYER_CHANGE  then  ;Z:0.4  ;HEIGHT:0.2
//   Orca/Bambu                 ; CHANGE_LAYER then  ; Z_HEIGHT: 0.4  ; LAYER_HEIGHT: 0.2
//   Simplify3D                 ; layer 3, Z = 0.600
// and the ;TYPE: feature comments. A user pattern (RE2) replaces the built-in
// markers when given; it is compiled once and tried on comment lines only.
#include <memory>
#include <string>
#include <string_view>

namespace re2 {
class RE2;
}

namespace gcode {

enum class MarkerKind : unsigned char { None, CuraLayer, LayerChange, ChangeLayer, Simplify3D, User };

struct CommentInfo {
  MarkerKind marker = MarkerKind::None;
  bool has_number = false;
  long number = 0;           // the slicer's layer number
  bool has_z = false;        // ;Z:, ; Z_HEIGHT:, or in the S3D marker
  double z = 0;
  bool has_height = false;   // ;HEIGHT:, ; LAYER_HEIGHT:
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

  // Classifies a comment (text after the ';' or inside the parentheses).
  CommentInfo classify(std::string_view comment_text) const;

 private:
  std::unique_ptr<re2::RE2> user_;
};

}  // namespace gcode
