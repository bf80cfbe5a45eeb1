#include "gcode/pipeline/selection.hpp"

#include <stdexcept>

#include "gcode/core/feature.hpp"

namespace gcode {

std::vector<std::string> split_list(std::string_view text) {
  std::vector<std::string> items;
  while (true) {
    std::size_t comma = text.find(',');
    std::string_view item = text.substr(0, comma);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    if (!item.empty()) items.emplace_back(item);
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  return items;
}

LayerSelection LayerSelection::parse(const SelectionText& text) {
  LayerSelection s;
  try {
    if (!text.layers.empty()) s.range_ = LayerRange::parse(text.layers);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--layers: ") + e.what());
  }
  try {
    if (!text.z_range.empty()) s.z_range_ = ZRange::parse(text.z_range);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--z-range: ") + e.what());
  }
  s.types_ = split_list(text.types);
  if (!text.types.empty() && s.types_.empty()) throw std::invalid_argument("--types: give ;TYPE: names, e.g. WALL-OUTER");
  return s;
}

bool LayerSelection::layer_selected(const LayerInfo& info) const {
  return (!range_ || range_->contains(info.index, total_)) && (!z_range_ || z_range_->contains(info.z));
}

void LayerSelection::enter_layer(const LayerInfo& info) {
  in_selected_layer_ = layer_selected(info);
  if (in_selected_layer_) ++layers_selected_;
}

bool LayerSelection::feature_selected(int feature) {
  if (types_.empty()) return true;
  if (feature < 0 || tracker_ == nullptr) return false;
  auto id = static_cast<std::size_t>(feature);
  if (id >= by_feature_.size()) by_feature_.resize(id + 1, -1);
  if (by_feature_[id] < 0) {
    by_feature_[id] = 0;
    const std::string& name = tracker_->feature_name(feature);
    for (std::size_t i = 0; i < types_.size(); ++i) {
      if (feature_matches(types_[i], name)) by_feature_[id] = 1;
    }
  }
  return by_feature_[id] == 1;
}

bool LayerSelection::selects(const TrackedLine& t) {
  if (by_layer() && !(t.region == Region::Layer && in_selected_layer_)) return false;
  // Features are the layers': the end code carries the last ;TYPE: (a park,
  // heaters off) but is none of them.
  if (!types_.empty() && t.region != Region::Layer) return false;
  return feature_selected(t.feature);
}

std::vector<std::string> LayerSelection::unmatched_types() const {
  std::vector<std::string> out;
  for (const std::string& wanted : types_) {
    bool found = false;
    for (int f = 0; tracker_ != nullptr && f < tracker_->feature_count() && !found; ++f)
      found = feature_matches(wanted, tracker_->feature_name(f));
    if (!found) out.push_back(wanted);
  }
  return out;
}

}  // namespace gcode
