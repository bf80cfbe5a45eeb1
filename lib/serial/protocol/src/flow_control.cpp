#include "gcode/serial/protocol/flow_control.hpp"

#include <algorithm>

namespace gcode::serial {

std::optional<FlowMode> parse_flow_mode(std::string_view name) {
  if (name == "ping-pong") return FlowMode::PingPong;
  if (name == "window") return FlowMode::Window;
  if (name == "advanced-ok") return FlowMode::AdvancedOk;
  if (name == "auto") return FlowMode::Auto;
  return std::nullopt;
}

const char* flow_mode_name(FlowMode mode) {
  switch (mode) {
    case FlowMode::PingPong: return "ping-pong";
    case FlowMode::Window: return "window";
    case FlowMode::AdvancedOk: return "advanced-ok";
    case FlowMode::Auto: return "auto";
  }
  return "?";
}

FlowControl::FlowControl(FlowMode mode, int queue, int rx_buffer)
    : mode_(mode), queue_(std::max(1, queue)), rx_(std::max(1, rx_buffer)) {}

bool FlowControl::may_send(std::size_t lines, std::size_t in_flight, std::size_t bytes) const {
  if (lines == 0) return true;
  if (effective() == FlowMode::PingPong) return false;
  // Marlin's ring buffer keeps one slot free: RX_BUFFER_SIZE - 1 bytes fit.
  return lines < static_cast<std::size_t>(queue_) && in_flight + bytes < static_cast<std::size_t>(rx_);
}

void FlowControl::on_ok(const Response& ok) {
  if (ok.queue_free < 0) return;
  advanced_seen_ = true;
  if (effective() != FlowMode::AdvancedOk) return;
  // B counts the free slots while the acknowledged command still holds its
  // own, so the queue has at least B + 1 slots. The first answer replaces the
  // configured guess; later ones can only raise it (a fuller queue reports less).
  int seen = ok.queue_free + 1;
  queue_ = learnt_ ? std::max(queue_, seen) : seen;
  learnt_ = true;
}

void FlowControl::firmware_has_advanced_ok() { advanced_seen_ = true; }

FlowMode FlowControl::effective() const {
  if (mode_ == FlowMode::Auto) return advanced_seen_ ? FlowMode::AdvancedOk : FlowMode::Window;
  return mode_;
}

}  // namespace gcode::serial
