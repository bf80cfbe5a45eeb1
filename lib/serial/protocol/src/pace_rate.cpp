#include "gcode/serial/protocol/pace_rate.hpp"

#include <algorithm>
#include <cmath>

namespace gcode::serial {

void PaceRate::sample(double factor, double moves) {
  if (!(factor > 0) || !(moves > 0)) return;
  // Down only: a sample is timing, which the host's latency bends either
  // way, and a factor above the printer's holds more moves in flight than
  // its planner takes (a pause stops later). Up is the floor's (at_least).
  const double w = std::min(1.0, moves / kSpan);
  factor_ = std::clamp(std::exp((1 - w) * std::log(factor_) + w * std::log(factor)), kMin, factor_);
}

void PaceRate::at_least(double factor) { factor_ = std::clamp(factor, factor_, kMax); }


}  // namespace gcode::serial
