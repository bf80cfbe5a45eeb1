#include "gcode/objects/object_table.hpp"

#include <algorithm>

#include "gcode/core/text.hpp"

namespace gcode {

int ObjectTable::find(const std::string& id_or_name) const {
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (objects[i].id == id_or_name) return static_cast<int>(i);
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (objects[i].name == id_or_name) return static_cast<int>(i);
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (iequals(objects[i].name, id_or_name)) return static_cast<int>(i);
  return -1;
}

ObjectTableStage::ObjectTableStage(const EstimatorOptions& estimate) { estimator_.emplace(estimate, static_cast<TimeSink*>(this)); }

ObjectTableStage::ObjectTableStage(Untimed what) : outlines_(what.outlines) {}

void ObjectTableStage::on_time(std::int64_t tag, double seconds) {
  const auto i = static_cast<std::size_t>(tag);
  if (times_.size() <= i) times_.resize(i + 1);
  times_[i] += seconds;
}

void ObjectTableStage::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  tracker_.layer();
  out.layer(info, before);
}

void ObjectTableStage::line(const TrackedLine& t, Emitter& out) {
  const int object = tracker_.line(t.line);
  if (estimator_) {
    estimator_->set_tag(object + 1);
    estimator_->add(t.line, t.move);
  }
  if (t.move.extruding && t.region == Region::Layer) {
    if (object < 0) {
      table_.outside.filament_mm += t.move.filament;
      if (t.feature >= 0 && std::find(outside_features_.begin(), outside_features_.end(), t.feature) == outside_features_.end())
        outside_features_.push_back(t.feature);
    } else {
      const auto i = static_cast<std::size_t>(object);
      if (table_.objects.size() <= i) table_.objects.resize(tracker_.names().size());
      if (hulls_.size() <= i) hulls_.resize(tracker_.names().size());
      PlateObject& o = table_.objects[i];
      if (o.first_layer == 0) o.first_layer = t.layer;
      o.last_layer = t.layer;
      o.filament_mm += t.move.filament;
      o.box.add(t.move.start[kX], t.move.start[kY]);
      o.box.add(t.move.end[kX], t.move.end[kY]);
      if (outlines_) {
        hulls_[i].add(t.move.start[kX], t.move.start[kY]);
        hulls_[i].add(t.move.end[kX], t.move.end[kY]);
      }
    }
  }
  out.pass(t);
}

void ObjectTableStage::finish(Emitter& out) {
  if (estimator_) estimator_->finish();
  const auto& names = tracker_.names();
  table_.objects.resize(names.size());
  hulls_.resize(names.size());
  times_.resize(names.size() + 1);
  for (std::size_t i = 0; i < names.size(); ++i) {
    PlateObject& o = table_.objects[i];
    o.id = names[i].id;
    o.name = names[i].name;
    o.outline = hulls_[i].hull();
    if (o.outline.size() < 3 && names[i].declared.size() >= 3) o.outline = names[i].declared;
    o.time_s = times_[i + 1];
  }
  table_.outside.time_s = times_[0];
  table_.dialect = tracker_.dialect();
  (void)out;
}

void ObjectTableStage::name_features(const LayerTracker& tracker) {
  table_.outside.features.clear();
  for (int f : outside_features_) table_.outside.features.push_back(tracker.feature_name(f));
}

}  // namespace gcode
