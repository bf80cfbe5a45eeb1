#include "gcode/report/layer_table.hpp"

#include <algorithm>
#include <numbers>

namespace gcode {

LayerTable::LayerTable() { start_.region = Region::StartCode; }

void LayerTable::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  LayerRow row;
  row.region = Region::Layer;
  row.info = info;
  layers_.push_back(row);
  out.layer(info, before);
}

void LayerTable::end_code(const EndCodeInfo& info, const MachineState& before, Emitter& out) {
  has_end_ = true;
  end_.region = Region::EndCode;
  out.end_code(info, before);
}

LayerRow& LayerTable::current() {
  if (has_end_) return end_;
  if (layers_.empty()) return start_;
  return layers_.back();
}

void LayerTable::line(const TrackedLine& t, Emitter& out) {
  out.pass(t);
  LayerRow& row = current();
  if (row.first_line == 0) {
    row.first_line = t.raw.number;
    row.byte_begin = t.raw.offset;
  }
  row.last_line = t.raw.number;
  row.byte_end = t.raw.offset + t.raw.size();
  ++total_lines_;
  total_bytes_ = row.byte_end;
  const Move& m = t.move;
  if (m.kind == MoveKind::Linear || m.kind == MoveKind::Arc) {
    ++row.moves;
    row.filament += m.filament;
    total_filament_ += m.filament;
    if (m.extruding) {
      row.extruded += m.filament;
      row.path += m.length;
      if (t.region == Region::Layer) {
        bounds_.add(m.start[kX], m.start[kY], m.start[kZ]);
        bounds_.add(m.end[kX], m.end[kY], m.end[kZ]);
      }
      if (t.feature >= 0 && std::find(row.features.begin(), row.features.end(), t.feature) == row.features.end())
        row.features.push_back(t.feature);
    } else if (m.travel) {
      row.travel += m.length;
    }
  }
}

double LayerTable::layers_extruded() const {
  double sum = 0;
  for (const LayerRow& r : layers_) sum += r.extruded;
  return sum;
}

double filament_mass_g(double length_mm, double diameter_mm, double density_g_cm3) {
  double area_mm2 = std::numbers::pi * diameter_mm * diameter_mm / 4;
  return length_mm * area_mm2 / 1000.0 * density_g_cm3;
}

}  // namespace gcode
