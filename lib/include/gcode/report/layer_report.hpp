#pragma once
// gc-layers' reports of a LayerTable: the human table and the JSON document.
//
// JSON schema (stable; new keys may be added, none removed or renamed):
// {
//   "schema": "gc-layers/1",
//   "file": "<name>",
//   "layer_mode": "markers" | "heuristic" | "spiral" (a vase without markers: one layer per turn),
//   "start_code": Region, "end_code": Region | null,
//   "layers": [ Layer ... ],
//   "summary": { "layers": n, "filament_mm": f (extruded in layers, as slicers count it),
//                "net_filament_mm": f (whole file, retractions subtracted), "filament_g": f, "density_g_cm3": f,
//                "filament_diameter_mm": f, "lines": n, "bytes": n,
//                "bounds": {"min": [x,y,z], "max": [x,y,z]} | null }
// }
// Region = { "first_line", "last_line", "byte_begin", "byte_end" (exclusive) }
// Layer  = Region + { "layer" (1-based), "slicer_layer" (int | null), "z", "height",
//                     "filament_mm" (net), "extruded_mm", "path_mm", "travel_mm",
//                     "moves", "features": [names], "empty": bool }
// Lines count from 1; a region with no line has first_line 0.
// With --time (ReportOptions::times set): every Region and Layer also has
// "time_s", every Layer "cumulative_s" (from the start of the file to its
// end), and the summary "time_s" and "time" ("h:mm:ss").
// With --time-by-feature (ReportOptions::features set) the summary also has
// "time_by_feature": {"features": {"<;TYPE: name>": s, ...}, "unnamed_s",
// "travel_s", "layer_change_s", "retract_s", "acceleration_s", "waits_s",
// "layers_s", "start_code_s", "end_code_s"} (feature_time.hpp: every move at
// its nominal speed, what acceleration costs on its own; they add up to layers_s).
#include <string>

#include "gcode/report/feature_time.hpp"
#include "gcode/report/layer_table.hpp"
#include "gcode/report/layer_time.hpp"

namespace gcode {

struct ReportOptions {
  std::string file_name;
  double density = 1.24;            // g/cm3 (PLA)
  double filament_diameter = 1.75;  // mm
  LayerMode mode = LayerMode::Markers;
  const LayerTimes* times = nullptr;  // --time: time columns and the total
  const FeatureTimes* features = nullptr;  // --time-by-feature: where the layers' time goes
};

class LayerTracker;

// `feature_name(id)` resolves feature ids (LayerTracker::feature_name).
std::string layer_table_text(const LayerTable& table, const LayerTracker& tracker, const ReportOptions& options);
// `s` as a JSON string, quotes and escapes included (every JSON the reports write).
void append_json_string(std::string& out, std::string_view s);

std::string layer_table_json(const LayerTable& table, const LayerTracker& tracker, const ReportOptions& options);

}  // namespace gcode
