#pragma once
// The paths of one lithophane layer, as in Jang & Hong's adaptive extrusion
// (background.md §3): an inner wall along the base surface, an outer wall
// following the picture, and between them one pass along the middle of the
// gap, as wide as the gap.
//
// Physics in two sentences: a bead's cross-section is A = W x H = q / v (q the
// extruder's volume rate, v the head speed), so at a constant q the head speed
// alone sets the width: v = q / (gap x layer height). The extruder rate is the
// quantity kept constant because the filament between gear and nozzle makes
// the extruder answer seconds late, while the head answers at once.
//
// How a layer is cut up ("column model"): at every position s along the base
// the layer's band is [0, t(s)] deep (t from the HeightMap, sampled at the
// middle of the layer). The inner wall takes [0, w], the outer wall
// [t - w, t] and the passes share [w, t - w] equally; all boundaries are
// linear between sample points, so the pieces tile the band exactly and each
// piece's volume is its strip's area x layer height.
// Sample points: candidates every `resolution` mm and at the picture's own
// corners (at a fixed height the thickness is linear between pixel centres,
// HeightMap::knots); kept are those the chord through the kept ones around
// would miss by more than `surface_tolerance` (Douglas-Peucker), so a hard
// edge or a one-pixel line is followed corner to corner while a straight
// stretch of surface is one piece (at most 5 mm on a plate; round a cylinder
// as long as the chord stays within 0.005 mm of the circle), and points
// where the count of passes would change within a stretch.
// A bead has one width per move, while the strip it fills widens or narrows
// along the piece (linearly): at the piece's ends two neighbouring beads
// then leave |change of one's depth + change of the other's| / 4 between
// them, measured across the band. Each stretch between sample points is cut
// into the fewest equal pieces that keep this at most `edge_gap` (pieces no
// shorter than half of `min_piece`); where a pass appears or ends (the walls
// stop sharing the band) the switch gets a piece of its own, short enough
// for the thickness's slope (down to 0.001 mm), so the change on either side
// of it is smooth. A flat plate's sample points lie on the written X's
// 0.0001 mm grid, so even the shortest piece's extent is written exactly.
// A piece's width at right angles to its path is area / length, so on a
// slope a bead gets thinner and faster, and its extruder rate stays q.
//   - q = line width x layer height x infill speed (what conventional infill
//     at that speed extrudes), capped by max flow. Walls keep their own rate,
//     line width x layer height x wall speed; where the band is thinner than
//     two line widths both walls share it (thinner and faster).
//   - Where the gap is narrower than min pass width there is no pass and the
//     walls share the band; where it is wider than max pass width it gets the
//     fewest equal passes that fit (the paper has one; thick parts need more).
//   - A speed outside [min speed, max speed] is clamped: the width is kept
//     (the band must be filled), so that piece's extruder rate changes. The
//     pieces are counted so a tool can warn once.
//   - The first layer runs at first_layer_factor x every rate (speed), for
//     adhesion of a part that stands on a thin edge.
// A flat plate's walls join into one loop (end caps across the thickness)
// like a slicer's perimeter; a cylinder's walls and full-length passes are
// closed rings. Memory is one layer: plan_layer fills a caller's buffer.
#include <cstdint>
#include <vector>

#include "gcode/litho/height_map.hpp"

namespace gcode::litho {

struct LithoOptions {
  double layer_height = 0.2;
  double nozzle = 0.4;
  double line_width = 0;          // mm; 0 = nozzle x 1.125
  double filament_diameter = 1.75;
  double wall_speed = 40;         // mm/s, both walls (the paper's base speed)
  double infill_speed = 100;      // mm/s of conventional infill that sets q (the paper's baseline)
  double max_flow = 12;           // mm3/s cap on q (what a common hot end melts)
  double min_speed = 5;           // mm/s
  double max_speed = 200;         // mm/s
  double max_pass_width = 0;      // mm; 0 = 2.5 x nozzle
  double min_pass_width = 0;      // mm; 0 = 0.5 x nozzle
  double resolution = 0.2;        // mm between sample points along the base
  double edge_gap = 0.04;         // mm: the widest gap cutting leaves beside a bead on steep parts
  double surface_tolerance = 0.02;  // mm: a pixel's corner is a sample point where the chord misses it by more
  double min_piece = 0.005;       // mm: the shortest piece cutting makes
  double first_layer_factor = 0.5;  // speed (and rate) factor on the first layer
  double center_x = 110;          // mm: where the lithophane stands on the bed
  double center_y = 110;

  // A copy with every "0 = default" field filled in.
  LithoOptions resolved() const;
  // Throws std::invalid_argument naming the option that makes no sense,
  // also for combinations with the map (--min thinner than the nozzle).
  void validate(const HeightMapOptions& map) const;
};

enum class PathRole : std::uint8_t { WallOuter, WallInner, Fill };

// One extruding move: from the previous piece's end (or the path's start) to `to`.
struct Piece {
  Point to;
  double width = 0;    // mm at right angles to the path
  double volume = 0;   // mm3 of plastic
  double speed = 0;    // mm/s commanded
  bool clamped = false;  // speed hit min or max speed: the width was kept, the rate changed
};

struct Path {
  PathRole role = PathRole::Fill;
  Point start;
  std::vector<Piece> pieces;
  // Set by order_layer (path_order.hpp): the travel from `from` to `start`
  // goes through `approach` and stays inside the layer's band, so it needs
  // no retraction. Unset: a plain travel.
  bool combed = false;
  Point from;
  std::vector<Point> approach;
};

struct LayerStats {
  double band_area = 0;   // mm2 the pieces' strips cover (the layer's cross-section as sampled)
  double volume = 0;      // mm3 of all pieces
  std::uint32_t pieces = 0;        // as planned, before straight runs of equal pieces are joined
  std::uint32_t clamped_fast = 0;  // pieces slowed to max speed
  std::uint32_t clamped_slow = 0;  // pieces sped up to min speed
  std::uint32_t fill_pieces = 0;
  int max_passes = 0;     // most passes side by side anywhere in the layer
};

struct LithoLayer {
  int index = 0;          // 0-based, bottom first
  double z = 0;           // nozzle height (top of the layer)
  double sample_z = 0;    // height at which the picture was sampled (middle of the layer)
  std::vector<Path> paths;  // in printing order
  LayerStats stats;
};

class LithophanePlanner {
 public:
  // `map` must outlive the planner. Throws std::invalid_argument for bad options.
  LithophanePlanner(const HeightMap& map, const LithoOptions& options);

  const LithoOptions& options() const { return options_; }  // resolved
  const HeightMap& map() const { return map_; }
  int layer_count() const { return layers_; }
  double layer_z(int index) const { return (index + 1) * options_.layer_height; }
  double fill_rate() const { return fill_rate_; }   // q, mm3/s (before the first-layer factor)
  double wall_rate() const { return wall_rate_; }   // mm3/s
  double filament_area() const { return filament_area_; }  // mm2
  // Bed XY of a point at `s` along the base and `depth` out from it.
  Point point_at(double s, double depth) const;

  // Plans layer `index` (0 .. layer_count()-1) into `out`, reusing its storage.
  void plan_layer(int index, LithoLayer& out) const;

 private:
  struct Column {
    double t;     // thickness
    double wall;  // depth of each wall
    double gap;   // depth left for passes (0: none)
  };
  struct Strip {  // one piece of a bead, from s0 to s1, depths [a, b] at each end
    double s0, a0, b0;
    double s1, a1, b1;
  };
  Column column(double s, double z) const;
  void keep_points(const std::vector<double>& cand, double z, std::vector<char>& keep) const;
  double longest_piece() const;
  int cuts_between(const Column& c0, const Column& c1, double length) const;
  double clamp_speed(double speed, Piece& piece, LayerStats& stats) const;
  static void push_piece(Path& path, const Piece& piece);
  bool add_strip(const Strip& strip, double rate, Path& path, LayerStats& stats) const;
  void add_cap(Point from, Point to, double rate, Path& path, LayerStats& stats) const;
  void plan_fill(const std::vector<double>& s, const std::vector<Column>& cols, double rate, LithoLayer& out) const;

  const HeightMap& map_;
  LithoOptions options_;
  int layers_ = 0;
  double fill_rate_ = 0;
  double wall_rate_ = 0;
  double filament_area_ = 0;
};

}  // namespace gcode::litho
