#pragma once
// The objects of a plate, read in one pass: for each, its id and name, the
// layers it spans, its box and outline on the plate (the convex hull of its
// extrusions), the filament it takes and its print time (the suite's
// estimator, report/estimator.hpp), and where it came from (the slicer's
// labels, or footprints: footprints.hpp). What was extruded outside every
// object (Cura's and ideaMaker's support, skirts, purge lines) is summed
// apart, with its ;TYPE: names.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gcode/objects/convex_hull.hpp"
#include "gcode/objects/object_tracker.hpp"
#include "gcode/pipeline/stage.hpp"
#include "gcode/report/estimator.hpp"

namespace gcode {

enum class ObjectSource : std::uint8_t { Labels, Footprint };

struct PlateObject {
  std::string id;
  std::string name;
  int first_layer = 0;  // 0: nothing of it was extruded
  int last_layer = 0;
  Box2 box;
  Polygon outline;      // convex hull of its extrusions (or the declared one)
  double filament_mm = 0;
  double time_s = 0;
  ObjectSource source = ObjectSource::Labels;
};

// What was printed in layers but in no object.
struct OutsideObjects {
  double filament_mm = 0;
  double time_s = 0;
  std::vector<std::string> features;  // the ;TYPE: names seen there, in order
};

struct ObjectTable {
  std::vector<PlateObject> objects;
  OutsideObjects outside;
  LabelDialect dialect = LabelDialect::None;
  // The object with this id, or else this name (exact; then ignoring case),
  // or -1.
  int find(const std::string& id_or_name) const;
};

// The table, built from the labels as the lines pass (a report: it changes nothing).
class ObjectTableStage : public Stage, private TimeSink {
 public:
  explicit ObjectTableStage(const EstimatorOptions& estimate = {});
  // Only what a filter needs: without times or outlines, only `outlines`
  // (Klipper's polygons) where asked. The estimator and the hulls are most
  // of the table's work.
  struct Untimed {
    bool outlines = false;
  };
  explicit ObjectTableStage(Untimed what);
  void line(const TrackedLine& t, Emitter& out) override;
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void finish(Emitter& out) override;
  // After the run.
  const ObjectTable& table() const { return table_; }
  // Names the ;TYPE: features seen outside the objects (after the run:
  // the pipeline's tracker knows the names).
  void name_features(const LayerTracker& tracker);

 private:
  void on_time(std::int64_t tag, double seconds) override;
  ObjectTracker tracker_;
  std::optional<Estimator> estimator_;
  bool outlines_ = true;
  std::vector<HullBuilder> hulls_;
  std::vector<double> times_;  // [0]: outside, [i + 1]: object i
  std::vector<int> outside_features_;
  ObjectTable table_;
};

}  // namespace gcode
