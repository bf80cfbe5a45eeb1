#include "gcode/transform/printed_height.hpp"

#include <cmath>

namespace gcode {

std::uint64_t PrintedHeight::key(double x, double y) const {
  // Cells of a +-1000 m bed fit in 32 bits each.
  const auto i = static_cast<std::int64_t>(std::floor(x / cell_));
  const auto j = static_cast<std::int64_t>(std::floor(y / cell_));
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) | static_cast<std::uint32_t>(j);
}

void PrintedHeight::add(double x, double y, double z) {
  if (!layer_.empty() && layer_.back().first == key(x, y)) {
    layer_.back().second = std::max(layer_.back().second, static_cast<float>(z));
    return;
  }
  layer_.emplace_back(key(x, y), static_cast<float>(z));
}

void PrintedHeight::next_layer() {
  for (const auto& [k, z] : layer_) {
    auto [it, fresh] = top_.emplace(k, z);
    if (!fresh && z > it->second) it->second = z;
  }
  layer_.clear();
}

double PrintedHeight::top(double x, double y, double none) const {
  const auto it = top_.find(key(x, y));
  return it == top_.end() ? none : it->second;
}

}  // namespace gcode
