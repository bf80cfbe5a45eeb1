#pragma once
// The print time of a generated lithophane, as gc-layers --time estimates it:
// the program is written once into the library's pipeline with the
// estimator's stage (nothing kept but one layer's text at a time), so the
// header of the real output can say ;TIME: before its first layer.
#include "gcode/litho/litho_gcode.hpp"
#include "gcode/report/estimator.hpp"

namespace gcode::litho {

// Seconds for the whole program (start and end code included).
double estimate_litho_seconds(const LithophanePlanner& planner, const LithoGcodeOptions& options,
                              const EstimatorOptions& estimator = {});

}  // namespace gcode::litho
