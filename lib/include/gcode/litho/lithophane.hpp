#pragma once
// The paths of one lithophane layer (Jang & Hong's adaptive extrusion): an
// inner wall along the base, an outer wall following the picture, and
// between them passes as wide as the gap, all at a constant extruder rate,
// so the head speed alone sets each bead's width (v = q / (width x layer
// height)). The band is cut into columns sampled at the picture's corners
// and every resolution step, and the pieces tile it exactly. The design, the
// cutting rules and the rates: docs/lithophanes.md. Memory is one layer:
// plan_layer fills a caller's buffer.
#include <algorithm>
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
  double infill_speed = 0;        // mm/s of conventional infill that sets q; 0 = q is max_flow
  double max_flow = 15;           // mm3/s: q, or its cap (what a 0.4 mm E3D V6-class hot end melts of PLA)
  double min_speed = 5;           // mm/s
  double max_speed = 200;         // mm/s
  double max_pass_width = 0;      // mm; 0 = 2.5 x nozzle
  double min_pass_width = 0;      // mm; 0 = 0.5 x nozzle
  double resolution = 0.2;        // mm between sample points along the base
  double edge_gap = 0.04;         // mm: the widest gap cutting leaves beside a bead on steep parts
  double surface_tolerance = 0.02;  // mm: a pixel's corner is a sample point where the chord misses it by more
  double min_piece = 0.005;       // mm: the shortest piece cutting makes
  double first_layer_factor = 0.5;  // speed (and rate) factor on the first layer
  bool base_wall = false;         // the base surface as a wall at wall speed (the paper's); else a bead at q
  double center_x = 110;          // mm: where the lithophane stands on the bed
  double center_y = 110;

  // A copy with every "0 = default" field filled in.
  LithoOptions resolved() const;
  // Throws std::invalid_argument naming the option that makes no sense,
  // also for combinations with the map (--min thinner than the nozzle).
  void validate(const HeightMapOptions& map) const;
};

// Base: the bead along the base surface, where the paper has its inner wall,
// at the passes' rate q (the picture does not need a wall there); it is
// ordered with the outer wall (one loop on a plate) and written as FILL.
enum class PathRole : std::uint8_t { WallOuter, WallInner, Base, Fill };

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

// Where the path ends: its last piece's end, or its start without pieces.
inline Point end_of(const Path& path) { return path.pieces.empty() ? path.start : path.pieces.back().to; }

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
    double extra = 0;  // the base bead's width beyond `wall` (widen_base)
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
  void add_fill_strip(const Strip& strip, int parts, double rate, Path& path, LayerStats& stats) const;
  void add_cap(Point from, Point to, double rate, Path& path, LayerStats& stats) const;
  static Strip wall_strip(double s0, const Column& c0, double s1, const Column& c1, bool outer);
  struct SampleRun;  // the sample points of a layer as they are laid down
  struct FillGrid;   // where the passes lie
  void sample_candidates(double first, double span, int n, std::vector<double>& cand) const;
  void sample_layer(double zs, std::vector<double>& s, std::vector<Column>& cols) const;
  void widen_base(std::vector<double>& s, std::vector<Column>& cols) const;
  void apply_base_extra(const std::vector<double>& extra, std::vector<double>& s, std::vector<Column>& cols) const;
  PathRole base_role() const;
  void plan_wall_rings(const std::vector<double>& s, const std::vector<Column>& cols, double rate, double base_rate,
                       LithoLayer& out) const;
  void plan_wall_loop(const std::vector<double>& s, const std::vector<Column>& cols, double rate, double base_rate,
                      LithoLayer& out) const;
  void plan_fill(const std::vector<double>& s, const std::vector<Column>& cols, double rate, LithoLayer& out) const;
  void plan_fill_rings(const FillGrid& grid, int count, double rate, LithoLayer& out) const;
  Point plan_fill_group(const FillGrid& grid, int k, int end, int count, Point cur, double rate, LithoLayer& out) const;

  const HeightMap& map_;
  LithoOptions options_;
  int layers_ = 0;
  double fill_rate_ = 0;
  double wall_rate_ = 0;
  double filament_area_ = 0;
};

}  // namespace gcode::litho
