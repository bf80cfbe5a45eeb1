// The lithophane checks of litho_check.hpp, compiled once into the test kit
// at the kit's optimisation (the sanitizer tree builds the test files
// themselves at -O0).
#include "litho_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace littest {

double band_volume(const HeightMap& map, double sample_z, double layer_height) {
  double area = 0;
  if (map.closed()) {
    const double r = map.base_radius();
    const int n = static_cast<int>(map.length() / 0.005);
    for (int i = 0; i < n; ++i) {
      const double t = map.thickness((i + 0.5) * map.length() / n, sample_z);
      area += ((r + t) * (r + t) - r * r) / 2 * (2 * std::numbers::pi / n);
    }
  } else {
    const int n = static_cast<int>(map.length() / 0.005);
    for (int i = 0; i < n; ++i) area += map.thickness((i + 0.5) * map.length() / n, sample_z) * map.length() / n;
  }
  return area * layer_height;
}

Coverage coverage(const std::vector<Bead>& beads, double ox, double oy, double ux, double uy, double lo, double hi,
                  double layer_height) {
  std::vector<std::pair<double, double>> spans;
  const double nx = -uy, ny = ux;  // normal of the ray
  for (const Bead& b : beads) {
    const double dx = b.x1 - b.x0, dy = b.y1 - b.y0;
    const double across = nx * dx + ny * dy;
    if (std::abs(across) < 1e-12 || b.length <= 0) continue;
    const double tau = (nx * (ox - b.x0) + ny * (oy - b.y0)) / across;
    if (tau < 0 || tau > 1) continue;
    const double px = b.x0 + tau * dx - ox, py = b.y0 + tau * dy - oy;
    const double r = ux * px + uy * py;
    if (r < 0) continue;
    const double width = b.filament * kFilamentArea / (b.length * layer_height);
    const double extent = width / 2 / (std::abs(across) / b.length);
    spans.emplace_back(r - extent, r + extent);
  }
  std::sort(spans.begin(), spans.end());
  Coverage c;
  if (spans.empty()) {
    c.max_gap = hi - lo;
    return c;
  }
  double reach = spans.front().second;
  for (const auto& [a, b] : spans) {
    if (a > reach) c.max_gap = std::max(c.max_gap, a - reach);
    reach = std::max(reach, b);
  }
  c.surface = std::max(std::abs(spans.front().first - lo), std::abs(reach - hi));
  return c;
}

Measured measure(const HeightMap& map, const LithophanePlanner& planner, const std::string& text,
                 double gap_step) {
  const LithoOptions& o = planner.options();
  const littest::Replayed r = littest::replay(text);
  Measured m;
  m.layers = r.layer_z.size();
  std::vector<std::vector<Bead>> layers(r.layer_z.size());
  for (const Bead& b : r.beads) layers[static_cast<std::size_t>(b.layer)].push_back(b);
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const double sample_z = (static_cast<double>(i) + 0.5) * o.layer_height;
    double volume = 0;
    for (const Bead& b : layers[i]) volume += b.filament * kFilamentArea;
    const double expected = band_volume(map, sample_z, o.layer_height);
    m.worst_volume_error = std::max(m.worst_volume_error, std::abs(volume / expected - 1));
    m.total_volume += volume;
    m.expected_volume += expected;
    // Gaps, on rays a little off the sample grid.
    if (map.closed()) {
      const double radius = map.base_radius();
      for (double s = 0.013; s < map.length(); s += gap_step) {
        const double a = s / radius;
        const Coverage c = coverage(layers[i], o.center_x, o.center_y, std::cos(a), std::sin(a), radius,
                                    radius + map.thickness(s, sample_z), o.layer_height);
        m.worst_gap = std::max(m.worst_gap, c.max_gap);
        m.worst_surface = std::max(m.worst_surface, c.surface);
      }
    } else {
      const double lw = o.line_width;
      const auto base = planner.point_at(0, 0);
      for (double s = lw + 0.013; s < map.length() - lw; s += gap_step) {
        const Coverage c = coverage(layers[i], base.x + s, base.y, 0, 1, 0, map.thickness(s, sample_z), o.layer_height);
        m.worst_gap = std::max(m.worst_gap, c.max_gap);
        m.worst_surface = std::max(m.worst_surface, c.surface);
      }
    }
    if (i == 0) continue;  // the first layer runs at half the rate
    // E is written with 7 decimals (the rounding carried), so a piece of a
    // micrometre, with E near 1e-5 mm, reads up to 1 % off the rate it was
    // given although the extruder, a step every 1e-3 mm of filament, cannot
    // tell. The rate is read over consecutive unclamped pieces together,
    // each reading with at least 1e-4 mm of filament (rounding <= 0.1 %).
    double filament = 0, seconds = 0;
    for (const Bead& b : layers[i]) {
      if (b.role != Role::Fill || b.feed >= o.max_speed * 60 || b.feed <= o.min_speed * 60) {  // clamped
        filament = seconds = 0;
        continue;
      }
      filament += b.filament;
      seconds += b.length / (b.feed / 60);
      if (filament < 1e-4) continue;
      const double rate = filament * kFilamentArea / seconds;
      m.worst_rate_error = std::max(m.worst_rate_error, std::abs(rate / planner.fill_rate() - 1));
      ++m.rate_pieces;
      filament = seconds = 0;
    }
  }
  return m;
}

}  // namespace littest
