#include "vase_check.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "test_support.hpp"

namespace meshtest {

namespace {

struct Seg {
  double ax, ay, bx, by;
};

double to_segment(double x, double y, const Seg& s) {
  const double dx = s.bx - s.ax, dy = s.by - s.ay, l2 = dx * dx + dy * dy;
  const double t = l2 > 0 ? std::clamp(((x - s.ax) * dx + (y - s.ay) * dy) / l2, 0.0, 1.0) : 0;
  return std::hypot(x - s.ax - t * dx, y - s.ay - t * dy);
}

// The mesh placed as gc-shape documents it, and its sections by brute force.
class Sections {
 public:
  Sections(const TestMesh& mesh, const VaseSetup& s) : tris_(mesh.triangles) {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (Tri& t : tris_)
      for (P3& p : t) {
        p = {p.x * s.scale, p.y * s.scale, p.z * s.scale};
        const double v[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], v[a]), hi[a] = std::max(hi[a], v[a]);
      }
    for (Tri& t : tris_)
      for (P3& p : t) p = {p.x - (lo[0] + hi[0]) / 2 + s.center_x, p.y - (lo[1] + hi[1]) / 2 + s.center_y, p.z - lo[2]};
    top_ = hi[2] - lo[2];
    bins_.resize(static_cast<std::size_t>(top_ / kBin) + 2);
    for (std::size_t i = 0; i < tris_.size(); ++i) {
      const auto [mn, mx] = std::minmax({tris_[i][0].z, tris_[i][1].z, tris_[i][2].z});
      for (auto b = static_cast<std::size_t>(mn / kBin); b <= static_cast<std::size_t>(mx / kBin) && b < bins_.size(); ++b)
        bins_[b].push_back(i);
    }
  }
  double top() const { return top_; }

  std::vector<Seg> at(double z) const {
    z = std::clamp(z, 1e-4, top_ - 1e-4);
    std::vector<Seg> out;
    for (std::size_t i : bins_[static_cast<std::size_t>(z / kBin)]) {
      double pts[4];
      int n = 0;
      for (int k = 0; k < 3 && n < 4; ++k) {
        const P3& a = tris_[i][k];
        const P3& b = tris_[i][(k + 1) % 3];
        if ((a.z < z) == (b.z < z)) continue;
        const double f = (z - a.z) / (b.z - a.z);
        pts[n++] = a.x + (b.x - a.x) * f;
        pts[n++] = a.y + (b.y - a.y) * f;
      }
      if (n == 4) out.push_back({pts[0], pts[1], pts[2], pts[3]});
    }
    return out;
  }

 private:
  static constexpr double kBin = 0.5;
  std::vector<Tri> tris_;
  std::vector<std::vector<std::size_t>> bins_;
  double top_ = 0;
};

bool inside(double x, double y, const std::vector<Seg>& section) {
  bool in = false;
  for (const Seg& s : section)
    if ((s.ay > y) != (s.by > y) && x < s.ax + (y - s.ay) / (s.by - s.ay) * (s.bx - s.ax)) in = !in;
  return in;
}

double distance(double x, double y, const std::vector<Seg>& lines) {
  double d = 1e300;
  for (const Seg& s : lines) d = std::min(d, to_segment(x, y, s));
  return d;
}

void judge_bottom(const Sections& sections, const std::vector<Seg>& beads, const VaseSetup& s, VaseCheck& c) {
  const std::vector<Seg> first = sections.at(s.layer_height / 2);
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (const Seg& g : first)
    for (const double* p : {&g.ax, &g.bx}) lo[0] = std::min(lo[0], p[0]), hi[0] = std::max(hi[0], p[0]), lo[1] = std::min(lo[1], p[1]), hi[1] = std::max(hi[1], p[1]);
  std::size_t far = 0;
  for (double x = lo[0]; x <= hi[0]; x += 0.4)
    for (double y = lo[1]; y <= hi[1]; y += 0.4) {
      if (!inside(x, y, first) || distance(x, y, first) < s.line_width) continue;
      const double d = distance(x, y, beads);
      ++c.bottom_points;
      c.bottom_gap = std::max(c.bottom_gap, d);
      if (d > s.line_width / 2 + 0.05) ++far;
    }
  c.bottom_far = c.bottom_points > 0 ? static_cast<double>(far) / c.bottom_points : 1;
}

}  // namespace

VaseCheck check_vase(const std::string& gcode, const TestMesh& mesh, const VaseSetup& s) {
  VaseCheck c;
  const Sections sections(mesh, s);
  c.model_top = sections.top();
  const double base = s.bottom_layers * s.layer_height;
  c.turns = std::max(1, static_cast<int>(std::ceil((c.model_top - base) / s.layer_height - 1e-9)));
  const double pitch = (c.model_top - base) / c.turns;
  const double area = std::numbers::pi * s.filament_diameter * s.filament_diameter / 4;
  const double flow = s.line_width * pitch / area;  // filament per mm of wall

  const gctest::LinePlace places = gctest::places_of(gcode);
  std::vector<Seg> first_layer;
  std::vector<double> turn_filament(static_cast<std::size_t>(c.turns) + 1, 0), turn_length(turn_filament);
  double last_z = -1;
  const std::vector<gctest::ReplayedMove> moves = gctest::replay_moves(gcode);
  std::size_t last_bead = 0;  // the end code follows it, in the last layer as the tracker counts
  for (const gctest::ReplayedMove& m : moves)
    if (m.move.extruding && m.move.filament > 0) last_bead = m.line_index;
  for (const gctest::ReplayedMove& m : moves) {
    const int layer = places.layer[m.line_index];  // 1-based, 0 outside the layers
    c.layers = std::max(c.layers, layer);
    if (layer == 0 || m.line_index > last_bead) continue;
    if (layer <= s.bottom_layers) {
      if (layer == 1 && m.move.extruding && m.move.filament > 0)
        first_layer.push_back({m.move.start[0], m.move.start[1], m.move.end[0], m.move.end[1]});
      continue;
    }
    c.z_fall = std::max(c.z_fall, last_z - m.move.end[2]);
    last_z = std::max(last_z, m.move.end[2]);
    // A travel, a retraction, a move of Z alone. A piece at the very start
    // of the ramp may carry too little filament for E's 5 decimals: E0 where
    // its bead (at most z - base high) needs under 1e-5 mm is not a travel.
    const double most = s.line_width * std::clamp(m.move.end[2] - base, 0.0, pitch) * m.move.length / area;
    const bool thin = m.move.filament == 0 && most < 1e-5;
    if (m.move.filament < 0 || m.move.xy_length == 0 || (!m.move.extruding && !thin)) {
      ++c.other_moves;
      continue;
    }
    const int turn = layer - s.bottom_layers - 1;  // 0-based: 0 is the ramp
    if (turn > 0 && turn <= c.turns) {
      turn_filament[static_cast<std::size_t>(turn)] += m.move.filament;
      turn_length[static_cast<std::size_t>(turn)] += m.move.length;
    }
    c.wall_top = std::max(c.wall_top, m.move.end[2]);
    const int samples = std::max(1, static_cast<int>(std::ceil(m.move.length / 0.2)));
    for (int k = 1; k <= samples; ++k) {
      const double t = static_cast<double>(k) / samples;
      const double x = m.move.start[0] + (m.move.end[0] - m.move.start[0]) * t;
      const double y = m.move.start[1] + (m.move.end[1] - m.move.start[1]) * t;
      const double z = m.move.start[2] + (m.move.end[2] - m.move.start[2]) * t;
      const std::vector<Seg> section = sections.at(z - pitch / 2);
      ++c.wall_samples;
      if (!inside(x, y, section)) ++c.outside;
      const double off = std::fabs(distance(x, y, section) - s.line_width / 2);
      if (off > c.worst_offset) c.worst_offset = off, c.worst_at[0] = x, c.worst_at[1] = y, c.worst_at[2] = z;
    }
  }
  for (int t = 1; t < c.turns; ++t)
    if (turn_length[static_cast<std::size_t>(t)] > 0)
      c.worst_flow = std::max(c.worst_flow, std::fabs(turn_filament[static_cast<std::size_t>(t)] /
                                                          turn_length[static_cast<std::size_t>(t)] / flow - 1));
  judge_bottom(sections, first_layer, s, c);
  return c;
}

}  // namespace meshtest
