#pragma once
// Layer selections as every tool takes them: "5", "5-9", "5-" (to the end),
// "-3" (the last three), "5,7,9-12". Layers are numbered as gc-layers prints
// them, the first printed layer being 1.
#include <string>
#include <string_view>
#include <vector>

namespace gcode {

class LayerRange {
 public:
  // Throws std::invalid_argument with a message naming the bad part.
  static LayerRange parse(std::string_view text);

  // Whether `layer` is selected in a file of `total` layers (total is only
  // needed for "-N"; pass 0 while the total is still unknown).
  bool contains(int layer, int total = 0) const;
  // Needs the total layer count to be known ("-3").
  bool needs_total() const;
  // The highest layer named explicitly (0 when open-ended), for errors such
  // as "layer 80 of a 60-layer file".
  int highest_named() const;
  // The lowest selected layer given the total.
  int lowest(int total) const;
  const std::string& text() const { return text_; }

 private:
  struct Span {
    int first;     // 1-based; for a "last N" span, N
    int last;      // inclusive; 0 = open end
    bool from_end; // "-N"
  };
  std::vector<Span> spans_;
  std::string text_;
};

// "Z1:Z2", either side may be empty ("0.2:", ":5"). Throws std::invalid_argument.
struct ZRange {
  double low = -1e300;
  double high = 1e300;
  static ZRange parse(std::string_view text);
  bool contains(double z) const { return z >= low - 1e-6 && z <= high + 1e-6; }
};

}  // namespace gcode
