#pragma once
// Print time by feature: where a print's time goes, for comparing two ways
// of printing the same part (gc-layers --time-by-feature, the lithophane
// benchmark). An Estimator fed with the pipeline's lines books each move's
// time in the layers to what it is:
//   - an extruding move: its ;TYPE: feature (Cura's WALL-OUTER, FILL, ...),
//   - a move without extrusion that changes Z: a layer change,
//   - any other move without extrusion: travel,
//   - an E-only move (and firmware retraction): retraction,
//   - G4, heating, homing: waits;
// each at its nominal speed all the way (length / speed), while what the
// machine loses below that speed, speeding up and slowing down at corners,
// starts and stops, is booked on its own as acceleration. So the parts add
// up to the layers' time exactly. Start and end code are one figure each.
#include <cstdint>
#include <string>
#include <vector>

#include "gcode/pipeline/stage.hpp"
#include "gcode/report/estimator.hpp"

namespace gcode {

struct FeatureTimes {
  struct Feature {
    std::string name;   // as the file spells it
    double seconds = 0; // at nominal speed
  };
  std::vector<Feature> features;  // in the order they first print
  double unnamed = 0;             // extrusion before any ;TYPE:
  double travel = 0;
  double layer_change = 0;
  double retract = 0;
  double acceleration = 0;        // lost below nominal speed, every kind of move in the layers
  double waits = 0;
  double start = 0;               // start code, all of it
  double end = 0;                 // end code, all of it
  // The layers' time: everything but start and end code.
  double layers() const;
  // The features whose kind is a wall (outer, inner, overhang) / the rest of the extrusion.
  double walls() const;
  double other_extrusion() const;
};

class FeatureTimer : public Stage, private TimeSink {
 public:
  explicit FeatureTimer(const EstimatorOptions& options = {});
  FeatureTimer(const FeatureTimer&) = delete;
  FeatureTimer& operator=(const FeatureTimer&) = delete;

  void line(const TrackedLine& t, Emitter& out) override;
  void finish(Emitter& out) override;

  // Final after finish(); `name(id)` resolves a feature id (LayerTracker::feature_name).
  template <typename Name> FeatureTimes times(Name&& name) const {
    FeatureTimes r = totals_;
    for (std::size_t i = 0; i < by_feature_.size(); ++i)
      if (by_feature_[i] > 0) r.features.push_back({std::string(name(static_cast<int>(i))), by_feature_[i]});
    return r;
  }

 private:
  void on_time(std::int64_t tag, double seconds) override;
  void on_motion(std::int64_t tag, double seconds, double cruise_seconds) override;

  Estimator estimator_;
  FeatureTimes totals_;
  std::vector<double> by_feature_;  // [feature id], cruise seconds
};

}  // namespace gcode
