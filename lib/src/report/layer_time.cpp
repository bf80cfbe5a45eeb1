#include "gcode/report/layer_time.hpp"

#include <fmt/format.h>

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

std::vector<std::string> time_change_lines(const LayerTimes& before, const LayerTimes& after,
                                           const std::vector<int>& layers) {
  auto seconds = [](double s) { return fmt::format("{:.1f} s", s); };
  std::vector<std::string> lines;
  for (int layer : layers) {
    auto i = static_cast<std::size_t>(layer - 1);
    if (i < before.layers.size() && i < after.layers.size())
      lines.push_back(fmt::format("layer {}: {} -> {}", layer, seconds(before.layers[i]), seconds(after.layers[i])));
  }
  const double t0 = before.total(), t1 = after.total();
  lines.push_back(fmt::format("estimated print time {} -> {} ({:+.1f} %)", format_duration(t0), format_duration(t1),
                              t0 > 0 ? 100 * (t1 - t0) / t0 : 0.0));
  return lines;
}

}  // namespace gcode
