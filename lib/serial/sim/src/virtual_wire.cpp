#include "gcode/serial/sim/virtual_wire.hpp"

#include <algorithm>
#include <cmath>

namespace gcode::serial {

void VirtualWire::receive(std::string_view bytes, double now) {
  if (bytes.empty()) return;
  if (head_ == in_.size()) {
    in_.clear();
    head_ = 0;
    next_ = std::max(now, next_) + byte_time_;
  }
  in_.append(bytes);
}

char VirtualWire::arrive() {
  char c = in_[head_++];
  next_ += byte_time_;
  if (head_ == in_.size()) {
    next_ -= byte_time_;  // the time the last byte arrived
    in_.clear();
    head_ = 0;
  }
  return c;
}

void VirtualWire::transmit(std::string_view line, double now) {
  transmit_bytes(line, now);
  transmit_bytes("\n", now);
}

void VirtualWire::transmit_bytes(std::string_view bytes, double now) {
  out_.append(bytes);
  out_free_at_ = std::max(out_free_at_, now) + static_cast<double>(bytes.size()) * byte_time_;
}

std::string_view VirtualWire::transmitted(double now) const {
  std::size_t pending = out_.size() - out_head_;
  if (pending == 0) return {};
  double left = (out_free_at_ - now) / byte_time_;  // bytes still on the way
  std::size_t not_done = left <= 0 ? 0 : static_cast<std::size_t>(std::ceil(left - 1e-6));
  std::size_t done = not_done >= pending ? 0 : pending - not_done;
  return std::string_view(out_).substr(out_head_, done);
}

void VirtualWire::take(std::size_t n) {
  out_head_ += n;
  if (out_head_ == out_.size()) {
    out_.clear();
    out_head_ = 0;
  } else if (out_head_ > (1u << 16)) {
    out_.erase(0, out_head_);
    out_head_ = 0;
  }
}

void VirtualWire::clear(double now) {
  in_.clear();
  head_ = 0;
  next_ = now;
  out_.clear();
  out_head_ = 0;
  out_free_at_ = now;
}

double VirtualWire::next_line_sent() const {
  if (out_head_ == out_.size()) return kNever;
  // Wake when the next whole line has been sent, not for every byte.
  std::size_t nl = out_.find('\n', out_head_);
  std::size_t upto = nl == std::string::npos ? out_.size() : nl + 1;
  return out_free_at_ - static_cast<double>(out_.size() - upto) * byte_time_;
}

}  // namespace gcode::serial
