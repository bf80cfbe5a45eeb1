#pragma once
// How many lines a sender may have in flight (sent, not yet acknowledged).
//
// Marlin keeps BUFSIZE commands in its queue and RX_BUFFER_SIZE bytes in its
// serial receive buffer; a byte that arrives while the buffer is full is lost
// (the line then fails its checksum and must be resent). While a blocking
// command runs (a G1 waiting for planner space, M109, G28) the firmware does
// not move lines from the buffer into the queue, so the only safe rule is
// GRBL's character counting: the bytes of every unacknowledged line together
// must fit into the receive buffer.
//
//  ping-pong    one line in flight: what OctoPrint and Printrun do. Each line
//               waits a full round trip, so the link idles between lines.
//  window       up to `queue` lines and `rx_buffer` bytes in flight.
//  advanced-ok  as window, but the queue size is learnt from the B field of
//               ADVANCED_OK answers ("ok N12 P15 B3"), and N acknowledges
//               every earlier line, so a lost "ok" costs nothing.
//  auto         advanced-ok when the firmware answers that way, else window.
#include <cstddef>
#include <optional>
#include <string_view>

#include "gcode/serial/protocol/protocol.hpp"

namespace gcode::serial {

enum class FlowMode : unsigned char { PingPong, Window, AdvancedOk, Auto };

std::optional<FlowMode> parse_flow_mode(std::string_view name);
const char* flow_mode_name(FlowMode mode);

class FlowControl {
 public:
  FlowControl(FlowMode mode, int queue, int rx_buffer);

  // Whether a line of `bytes` bytes may go out with `lines` lines and
  // `in_flight` bytes already unacknowledged. A line longer than the whole
  // buffer may still go alone.
  bool may_send(std::size_t lines, std::size_t in_flight, std::size_t bytes) const;

  // Learns from an "ok": ADVANCED_OK fields switch auto mode over and tell
  // the real queue size.
  void on_ok(const Response& ok);
  // The firmware said in M115 that it answers with ADVANCED_OK.
  void firmware_has_advanced_ok();

  // The mode in effect now (auto resolves to window or advanced-ok).
  FlowMode effective() const;
  FlowMode requested() const { return mode_; }
  // ok N<n> acknowledges all lines up to n (ADVANCED_OK in effect).
  bool ok_numbers_acknowledge() const { return effective() == FlowMode::AdvancedOk && advanced_seen_; }
  int queue() const { return queue_; }
  int rx_buffer() const { return rx_; }

 private:
  FlowMode mode_;
  int queue_;
  int rx_;
  bool advanced_seen_ = false;
  bool learnt_ = false;
};

}  // namespace gcode::serial
