#pragma once
// Print time per layer: an Estimator fed from a LayerTracker's lines, its
// time booked to the start code, each layer, and the end code.
#include <cstdint>
#include <vector>

#include "gcode/report/estimator.hpp"
#include "gcode/core/layer_tracker.hpp"

namespace gcode {

struct LayerTimes {
  double start = 0;            // seconds in the start code (heating, homing, purge line)
  std::vector<double> layers;  // [i] = layer i + 1
  double end = 0;              // end code
  double total() const;
  // Seconds from the start of the file to the end of layer `index` (1-based).
  double cumulative(int index) const;
};

class LayerTimer : private TimeSink {
 public:
  explicit LayerTimer(const EstimatorOptions& options = {});
  LayerTimer(const LayerTimer&) = delete;
  LayerTimer& operator=(const LayerTimer&) = delete;

  // Call from LayerSink::on_line for every line, in order.
  void on_line(const TrackedLine& t);
  // End of input.
  void finish();

  const LayerTimes& times() const { return times_; }
  const Estimator& estimator() const { return estimator_; }

 private:
  void on_time(std::int64_t tag, double seconds) override;

  Estimator estimator_;
  LayerTimes times_;
};

}  // namespace gcode
