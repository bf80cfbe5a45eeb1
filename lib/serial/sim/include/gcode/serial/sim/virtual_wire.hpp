#pragma once
// The serial link of the virtual printer (virtual_printer.hpp), in simulated
// seconds: baud/10 bytes a second in each direction. The host's bytes reach
// the printer one byte time apart, after what is already on the wire; the
// printer's lines go out after what it is still sending, and the host takes
// what has fully arrived. Nothing is lost on the wire itself: the printer's
// receive buffer (and what overruns it) is the printer's.
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>

namespace gcode::serial {

class VirtualWire {
 public:
  static constexpr double kNever = std::numeric_limits<double>::infinity();

  explicit VirtualWire(double baud) : byte_time_(10.0 / baud) {}
  double byte_time() const { return byte_time_; }

  // Host to printer: bytes written at `now`.
  void receive(std::string_view bytes, double now);
  // When the next byte reaches the printer (kNever: none on the way).
  double next_arrival() const { return head_ < in_.size() ? next_ : kNever; }
  // The byte that arrives at next_arrival().
  char arrive();

  // Printer to host: a line (the newline added) starts after what is still
  // going out, no earlier than `now`.
  void transmit(std::string_view line, double now);
  // Bytes without a newline: the start of a line a reset cut short.
  void transmit_bytes(std::string_view bytes, double now);
  // Bytes fully sent by `now`; the host takes them with take(n).
  std::string_view transmitted(double now) const;
  void take(std::size_t n);
  // The link is cut at `now`: whatever was on the way, either way, is lost.
  void clear(double now);
  // When the next whole line has been sent (kNever: nothing to send).
  double next_line_sent() const;

 private:
  double byte_time_;
  std::string in_;              // host -> printer, not arrived yet from head_ on
  std::size_t head_ = 0;
  double next_ = 0;             // arrival time of in_[head_]
  std::string out_;             // printer -> host, not taken yet from out_head_ on
  std::size_t out_head_ = 0;
  double out_free_at_ = 0;      // when the last byte of out_ is sent
};

}  // namespace gcode::serial
