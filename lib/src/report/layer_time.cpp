#include "gcode/report/layer_time.hpp"

namespace gcode {

namespace {
// Tags: a layer's index, 0 for the start code, -1 for the end code.
constexpr std::int64_t kEndTag = -1;
}  // namespace

double LayerTimes::total() const {
  double t = start + end;
  for (double s : layers) t += s;
  return t;
}

double LayerTimes::cumulative(int index) const {
  double t = start;
  for (int i = 0; i < index && i < static_cast<int>(layers.size()); ++i) t += layers[static_cast<std::size_t>(i)];
  return t;
}

LayerTimer::LayerTimer(const EstimatorOptions& options) : estimator_(options, this) {}

void LayerTimer::line(const TrackedLine& t, Emitter& out) {
  out.pass(t);
  estimator_.set_tag(t.region == Region::EndCode ? kEndTag : (t.region == Region::Layer ? t.layer : 0));
  estimator_.add(t.line, t.move);
}

void LayerTimer::finish(Emitter&) { estimator_.finish(); }

void LayerTimer::on_time(std::int64_t tag, double seconds) {
  if (tag == kEndTag) {
    times_.end += seconds;
  } else if (tag <= 0) {
    times_.start += seconds;
  } else {
    auto index = static_cast<std::size_t>(tag - 1);
    if (times_.layers.size() <= index) times_.layers.resize(index + 1, 0.0);
    times_.layers[index] += seconds;
  }
}

}  // namespace gcode
