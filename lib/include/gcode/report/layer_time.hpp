#pragma once
// Print time per layer: an Estimator fed with the pipeline's lines, its time
// booked to the start code, each layer, and the end code. A report stage.
#include <cstdint>
#include <string>
#include <vector>

#include "gcode/report/estimator.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gcode {

struct LayerTimes {
  double start = 0;            // seconds in the start code (heating, homing, purge line)
  std::vector<double> layers;  // [i] = layer i + 1
  double end = 0;              // end code
  double total() const;
  // Seconds from the start of the file to the end of layer `index` (1-based).
  double cumulative(int index) const;
};

// The estimate before and after a change, for the user: one line for each
// of `layers` both know ("layer 4: 12.3 s -> 8.1 s"), then the total
// ("estimated print time 0:12:03 -> 0:10:40 (-11.5 %)").
std::vector<std::string> time_change_lines(const LayerTimes& before, const LayerTimes& after,
                                           const std::vector<int>& layers);

class LayerTimer : public Stage, private TimeSink {
 public:
  explicit LayerTimer(const EstimatorOptions& options = {});
  LayerTimer(const LayerTimer&) = delete;
  LayerTimer& operator=(const LayerTimer&) = delete;

  void line(const TrackedLine& t, Emitter& out) override;
  // The end of the input: the moves still in the look-ahead are timed.
  void finish(Emitter& out) override;

  const LayerTimes& times() const { return times_; }
  const Estimator& estimator() const { return estimator_; }

 private:
  void on_time(std::int64_t tag, double seconds) override;

  Estimator estimator_;
  LayerTimes times_;
};

}  // namespace gcode
