#include "gcode/serial/control/pause_log.hpp"

#include <utility>

namespace gcode::serial {

PauseRecord& PauseLog::start(std::string request, int layer, double wall_now, double printer_time) {
  PauseRecord r;
  r.request = std::move(request);
  r.layer = layer;
  r.wall_request = wall_now;
  r.printer_request = printer_time;
  records_.push_back(std::move(r));
  return records_.back();
}

void PauseLog::resumed(double wall_now) {
  PauseRecord& r = records_.back();
  if (r.wall_paused < 0) r.wall_paused = wall_now;
  resumed_seconds_ += wall_now - r.wall_paused;
}

double PauseLog::paused_seconds(double wall_now, bool paused) const {
  double s = resumed_seconds_;
  if (paused && !records_.empty() && records_.back().wall_paused >= 0) s += wall_now - records_.back().wall_paused;
  return s;
}

}  // namespace gcode::serial
