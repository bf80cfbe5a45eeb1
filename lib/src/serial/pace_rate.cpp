#include "gcode/serial/pace_rate.hpp"

#include <algorithm>
#include <cmath>

namespace gcode::serial {

void PaceRate::sample(double factor, double moves) {
  if (!(factor > 0) || !(moves > 0)) return;
  const double w = std::min(1.0, moves / kSpan);
  factor_ = std::clamp(std::exp((1 - w) * std::log(factor_) + w * std::log(factor)), kMin, kMax);
}

void PaceRate::faster() { factor_ = std::min(kMax, factor_ * kStep); }

}  // namespace gcode::serial
