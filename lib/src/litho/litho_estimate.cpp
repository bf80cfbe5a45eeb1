#include "gcode/litho/litho_estimate.hpp"

#include "gcode/core/layer_marker.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/report/layer_time.hpp"

namespace gcode::litho {

double estimate_litho_seconds(const LithophanePlanner& planner, const LithoGcodeOptions& options,
                              const EstimatorOptions& estimator) {
  const LayerMarkers markers;
  Pipeline pipeline(markers);
  LayerTimer timer(estimator);
  pipeline.add(timer);
  LithoGcodeOptions quiet = options;
  quiet.estimated_seconds = 0;
  write_litho_gcode(planner, quiet, [&](std::string_view chunk) { pipeline.feed(chunk); });
  pipeline.finish();
  return timer.times().total();
}

}  // namespace gcode::litho
