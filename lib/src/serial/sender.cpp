#include "gcode/serial/sender.hpp"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "gcode/core/line.hpp"

namespace gcode::serial {

namespace {

// Commands whose "ok" legitimately takes long: heating waits, homing, probing,
// dwell, waiting for the moves to finish.
bool is_long_running(const Line& line) {
  return line.is_m(109) || line.is_m(190) || line.is_m(191) || line.is_m(303) || line.is_m(400) || line.is_g(28) ||
         line.is_g(29) || line.is_g(4) || line.is_g(34) || line.is_g(33) || line.is_m(600) || line.is_m(0) ||
         line.is_m(1);
}

}  // namespace

Sender::Sender(const SenderConfig& config, Logger log)
    : config_(config), log_(std::move(log)), flow_(config.flow, config.queue, config.rx_buffer), ring_(2048) {}

void Sender::start(double now) {
  last_rx_ = last_any_rx_ = now;
  handshake_start_ = handshake_retry_ = now;
  if (config_.handshake) {
    state_ = SenderState::Handshake;
    // Unnumbered: Marlin only checks numbers on lines that start with N, and
    // M110 N0 makes the next numbered line N1.
    send_unnumbered("M110 N0", false, false);
  } else {
    state_ = SenderState::Printing;
    fill(now);
  }
}

void Sender::grow_ring() {
  std::vector<Slot> bigger(ring_.size() * 2);
  long long from = std::max<long long>(1, next_send_ - kHistory);
  for (long long n = from; n < next_number_; ++n)
    bigger[static_cast<std::size_t>(n) & (bigger.size() - 1)] = std::move(slot(n));
  ring_.swap(bigger);
}

void Sender::submit(std::string_view command, std::uint64_t source_line, int layer) {
  if (command.empty() || cancelled_) return;
  if (next_number_ - std::max<long long>(1, next_send_ - kHistory) >= static_cast<long long>(ring_.size())) grow_ring();
  Slot& s = slot(next_number_);
  s.wire.clear();  // keeps its capacity: no allocation per line once warm
  append_numbered_line(s.wire, next_number_, command);
  s.source_line = source_line;
  s.layer = layer;
  Line line = Line::parse(command);
  s.long_running = is_long_running(line);
  s.temperature_query = line.is_m(105);
  ++next_number_;
}

void Sender::end_of_input() {
  input_done_ = true;
}

void Sender::pump(double now) {
  fill(now);
  check_done(now);
}

void Sender::send_unnumbered(std::string_view command, bool temperature_query, bool track) {
  out_ += command;
  out_ += '\n';
  if (trace_) log_(LogLevel::Trace, fmt::format("-> {}", command));
  if (track) {
    flight_.push_back({-1, static_cast<std::uint32_t>(command.size() + 1), temperature_query});
    flight_bytes_ += command.size() + 1;
  }
}

void Sender::written(std::size_t n, double now) {
  out_pos_ += n;
  stats_.bytes += n;
  if (out_pos_ == out_.size()) {
    out_.clear();
    out_pos_ = 0;
  }
  if (n > 0 && settling_) settle_from_ = std::max(settle_from_, now);
}

bool Sender::settled(double now) const {
  return output().empty() && flight_.empty() && now >= settle_from_ + settle_quiet_ &&
         now >= last_any_rx_ + settle_quiet_;
}

void Sender::fill(double now) {
  if (state_ != SenderState::Printing || paused_ || cancelled_) return;
  if (settling_) {
    if (!settled(now)) return;
    settling_ = false;
  }
  if (input_done_ && !final_queued_ && next_send_ == next_number_ && config_.finish_with_m400) {
    final_queued_ = true;
    submit("M400", 0, last_acked_.layer);
  }
  while (next_send_ < next_number_) {
    const Slot& s = slot(next_send_);
    if (!flow_.may_send(flight_.size(), flight_bytes_, s.wire.size())) break;
    out_ += s.wire;
    if (trace_) log_(LogLevel::Trace, fmt::format("-> {} @{:.6f}", std::string_view(s.wire).substr(0, s.wire.size() - 1), now));
    flight_.push_back({next_send_, static_cast<std::uint32_t>(s.wire.size()), s.temperature_query});
    flight_bytes_ += s.wire.size();
    if (next_send_ > highest_sent_) {
      highest_sent_ = next_send_;
      ++stats_.lines;
      stats_.payload_bytes += s.wire.size();
      if (stats_.print_start < 0) stats_.print_start = now;
    } else {
      ++stats_.resent_lines;
    }
    if (flight_.size() == 1) last_rx_ = std::max(last_rx_, now);  // the timeout runs from the first line in flight
    ++next_send_;
  }
  check_done(now);
}

void Sender::check_done(double now) {
  if (state_ == SenderState::Printing && input_done_ && (final_queued_ || !config_.finish_with_m400) &&
      next_send_ == next_number_ && flight_.empty() && !settling_) {
    state_ = SenderState::Done;
    stats_.print_end = now;
  }
  if (cancelled_ && state_ != SenderState::Failed && flight_.empty()) state_ = SenderState::Cancelled;
}

void Sender::acknowledge_front() {
  const Flight f = flight_.front();
  flight_.pop_front();
  flight_bytes_ -= f.bytes;
  if (f.number > last_acked_.number) {
    const Slot& s = slot(f.number);
    last_acked_.number = f.number;
    if (s.source_line != 0) {
      last_acked_.source_line = s.source_line;
      last_acked_.layer = s.layer;
    }
  }
}

void Sender::on_ok(const Response& r, double now) {
  ++stats_.oks;
  timeouts_in_row_ = 0;
  last_rx_ = now;
  flow_.on_ok(r);
  if (state_ == SenderState::Handshake) {
    state_ = SenderState::Capabilities;
    handshake_retry_ = now;
    send_unnumbered("M115", false, false);
    return;
  }
  if (state_ == SenderState::Capabilities) {
    // The answer to M115, or a late answer to a repeated M110 (one sent
    // after the greeting of a board that was still booting). Printing starts
    // once the link has been quiet for a moment, so no such extra "ok" can
    // be taken for the first line's.
    if (caps_answered_) ++stats_.stray_oks;
    caps_answered_ = true;
    return;
  }
  if (expect_error_ok_) {
    // Marlin answers a rejected line with Error, Resend and "ok": that ok
    // belongs to the rejected line, which already left the flight list.
    expect_error_ok_ = false;
    return;
  }
  if (flight_.empty()) {
    ++stats_.stray_oks;
  } else if (flow_.ok_numbers_acknowledge() && r.line >= 0) {
    // ok N<n>: everything sent before line n has been executed too.
    while (!flight_.empty() && flight_.front().number <= r.line) acknowledge_front();
  } else if (r.has_temperature) {
    // The answer to our M105 (or one in the file): Marlin runs commands in
    // order, so every line sent before it is done.
    auto it = std::find_if(flight_.begin(), flight_.end(), [](const Flight& f) { return f.temperature_query; });
    if (it == flight_.end()) {
      acknowledge_front();
    } else {
      std::size_t count = static_cast<std::size_t>(it - flight_.begin()) + 1;
      for (std::size_t i = 0; i < count; ++i) acknowledge_front();
    }
  } else {
    acknowledge_front();
  }
  if (flight_.empty() && stats_.print_start >= 0) stats_.print_end = now;
  fill(now);
}

void Sender::on_resend(long long n, double now) {
  expect_error_ok_ = true;
  if (state_ != SenderState::Printing) return;
  if (n >= next_send_) {
    // Nothing sent from there on: a request for the line about to go out.
    ++stats_.duplicate_resends;
    return;
  }
  if (n < std::max<long long>(1, next_send_ - kHistory) || n < 1) {
    fail(fmt::format("the printer asked to resend line {}, which is no longer in the history (sent up to {})", n,
                     next_send_ - 1));
    return;
  }
  if (settling_ && n == settle_line_) {
    // An echo of the request we are already handling: a line that was on
    // the wire behind the bad one failed too.
    ++stats_.duplicate_resends;
    return;
  }
  if (n == resend_line_) {
    if (++resend_count_ > config_.max_resends) {
      fail(fmt::format("the printer asked for line {} {} times; giving up", n, resend_count_));
      return;
    }
  } else {
    resend_line_ = n;
    resend_count_ = 1;
  }
  ++stats_.resend_requests;
  // Everything from line n on is lost or will be rejected: take it out of
  // the flight list (with anything sent after it) and send it again.
  auto first = std::find_if(flight_.begin(), flight_.end(), [n](const Flight& f) { return f.number >= n; });
  std::size_t stale_bytes = 0;
  for (auto it = first; it != flight_.end(); ++it) stale_bytes += it->bytes;
  flight_bytes_ -= stale_bytes;
  flight_.erase(first, flight_.end());
  next_send_ = n;
  settling_ = true;
  settle_line_ = n;
  settle_from_ = now;
  // Long enough for the stale lines to reach the printer and be rejected.
  double rate = std::max(1.0, config_.link_bytes_per_second);
  settle_quiet_ = std::clamp(2.0 * static_cast<double>(stale_bytes + output().size() + 64) / rate, 0.002, 0.5);
  log_(LogLevel::Info, fmt::format("resend from {}", describe({n, slot(n).source_line, slot(n).layer})));
}

void Sender::on_capability(std::string_view text) {
  auto cap = [&](std::string_view name) {
    std::string key = fmt::format("Cap:{}:1", name);
    return text.find(key) != std::string_view::npos;
  };
  if (text.rfind("FIRMWARE_NAME:", 0) == 0) {
    std::size_t end = text.find(" SOURCE_CODE_URL");
    firmware_.name = std::string(text.substr(14, end == std::string_view::npos ? std::string_view::npos : end - 14));
    auto number_after = [&](std::string_view key) {
      std::size_t p = text.find(key);
      if (p == std::string_view::npos) return 0.0;
      return std::atof(std::string(text.substr(p + key.size(), 24)).c_str());
    };
    firmware_.time_scale = number_after("TIME_SCALE:");
    firmware_.baud = number_after("BAUD:");
    // A simulated printer's link runs at its own pace, not the port's.
    if (firmware_.time_scale > 0 && firmware_.baud > 0)
      config_.link_bytes_per_second = firmware_.baud / 10 * firmware_.time_scale;
  }
  if (cap("ADVANCED_OK")) {
    firmware_.advanced_ok = true;
    flow_.firmware_has_advanced_ok();
  }
  if (cap("EMERGENCY_PARSER")) firmware_.emergency_parser = true;
  if (cap("AUTOREPORT_TEMP")) firmware_.autoreport_temp = true;
  if (cap("BUSY_PROTOCOL") || cap("HOST_ACTION_COMMANDS")) firmware_.busy_protocol = true;
}

void Sender::on_line(std::string_view text, double now) {
  if (trace_) log_(LogLevel::Trace, fmt::format("<- {} @{:.6f}", text, now));
  last_any_rx_ = now;
  if (settling_) settle_from_ = std::max(settle_from_, now);
  Response r = parse_response(text);
  if (r.kind != ResponseKind::Ok && r.kind != ResponseKind::Resend && r.kind != ResponseKind::Empty)
    expect_error_ok_ = false;
  switch (r.kind) {
    case ResponseKind::Empty: break;
    case ResponseKind::Ok: on_ok(r, now); break;
    case ResponseKind::Resend:
      last_rx_ = now;
      timeouts_in_row_ = 0;
      on_resend(r.line, now);
      break;
    case ResponseKind::Error:
      ++stats_.errors;
      last_rx_ = now;
      if (r.error == ErrorClass::Fatal) {
        fail(fmt::format("the printer reported a fatal error: {}; last acknowledged: {}", r.text, describe(last_acked_)));
      } else if (r.error == ErrorClass::Recoverable) {
        log_(LogLevel::Warning, fmt::format("printer: Error:{}", r.text));
      } else {
        log_(LogLevel::Info, fmt::format("printer: Error:{}", r.text));
      }
      break;
    case ResponseKind::Busy:
      ++stats_.busy;
      timeouts_in_row_ = 0;
      last_rx_ = now;
      last_busy_ = now;
      break;
    case ResponseKind::Action:
      log_(LogLevel::Warning, fmt::format("printer action: {}", r.text));
      if (r.text.rfind("pause", 0) == 0 && r.text.rfind("paused", 0) != 0) paused_ = true;
      if (r.text.rfind("resume", 0) == 0 && r.text.rfind("resumed", 0) != 0) paused_ = false;
      if (r.text.rfind("cancel", 0) == 0) cancel();
      break;
    case ResponseKind::Temperature:
      // Heating waits (M109/M190) report temperatures instead of "busy".
      if (!flight_.empty() && flight_.front().number > 0 && slot(flight_.front().number).long_running) last_rx_ = now;
      break;
    case ResponseKind::Capability:
      on_capability(r.text);
      break;
    case ResponseKind::Start:
      if (state_ == SenderState::Handshake) {
        send_unnumbered("M110 N0", false, false);
      } else if (state_ == SenderState::Printing) {
        fail("the printer restarted (it said \"start\")");
      }
      break;
    case ResponseKind::Echo:
      log_(LogLevel::Info, fmt::format("printer: {}", r.text));
      break;
    case ResponseKind::Wait:
      break;
    case ResponseKind::Unknown:
      ++stats_.unknown;
      log_(LogLevel::Info, fmt::format("printer: {}", r.text));
      break;
  }
  fill(now);
  check_done(now);
}

double Sender::current_timeout() const {
  double t = config_.timeout;
  bool long_running = false;
  for (const Flight& f : flight_)
    if (f.number > 0 && slot(f.number).long_running) long_running = true;
  if (long_running) t *= 6;
  if (last_rx_ - last_busy_ < config_.timeout) t *= 2;  // a busy firmware gets more time
  return t;
}

double Sender::deadline() const {
  if (finished()) return 1e300;
  if (state_ == SenderState::Capabilities && caps_answered_) return last_any_rx_ + kQuietStart;
  if (state_ == SenderState::Handshake || state_ == SenderState::Capabilities)
    return std::min(handshake_retry_ + std::min(1.0, config_.timeout / 3), handshake_start_ + config_.timeout);
  double d = 1e300;
  if (settling_ && flight_.empty()) d = std::max(settle_from_, last_any_rx_) + settle_quiet_;
  if (!flight_.empty()) d = std::min(d, last_rx_ + current_timeout());
  return d;
}

void Sender::on_timer(double now) {
  if (finished()) return;
  if (state_ == SenderState::Capabilities && caps_answered_ && now >= last_any_rx_ + kQuietStart) {
    state_ = SenderState::Printing;
    if (firmware_.advanced_ok) flow_.firmware_has_advanced_ok();
    fill(now);
    return;
  }
  if (state_ == SenderState::Handshake || state_ == SenderState::Capabilities) {
    if (now >= handshake_start_ + config_.timeout) {
      if (state_ == SenderState::Capabilities) {
        // The firmware answered M110 but not M115: print without its capabilities.
        state_ = SenderState::Printing;
        fill(now);
        return;
      }
      fail(fmt::format("no answer from the printer within {} s (is the baud rate right?)", config_.timeout));
      return;
    }
    if (now >= handshake_retry_ + std::min(1.0, config_.timeout / 3)) {
      handshake_retry_ = now;
      send_unnumbered(state_ == SenderState::Handshake ? "M110 N0" : "M115", false, false);
    }
    return;
  }
  if (!flight_.empty() && now >= last_rx_ + current_timeout()) {
    ++stats_.timeouts;
    if (++timeouts_in_row_ > config_.max_timeouts) {
      fail(fmt::format("the printer stopped answering ({} timeouts of {} s in a row); last acknowledged: {}",
                       timeouts_in_row_ - 1, config_.timeout, describe(last_acked_)));
      return;
    }
    log_(LogLevel::Warning, fmt::format("no answer for {:.3g} s; asking with M105", now - last_rx_));
    last_rx_ = now;
    // An earlier probe whose answer got lost (or garbled into a plain "ok")
    // would hold its place for ever: the new one replaces it.
    for (auto it = flight_.begin(); it != flight_.end();) {
      if (it->number < 0) {
        flight_bytes_ -= it->bytes;
        it = flight_.erase(it);
      } else {
        ++it;
      }
    }
    send_unnumbered("M105", true, true);
  }
  fill(now);
}

void Sender::disconnected(std::string_view why) {
  if (finished()) return;
  fail(fmt::format("lost the connection to the printer ({}); last acknowledged: {}", why, describe(last_acked_)));
}

void Sender::cancel() {
  if (cancelled_) return;
  cancelled_ = true;
  input_done_ = true;
  next_number_ = next_send_;  // drop what was not sent yet
  check_done(0);
}

void Sender::emergency_stop() {
  cancel();
  emergency_ = true;
  // Out of order: whatever was queued for the port is dropped; the newline
  // ends a line that went out halfway. Marlin's emergency parser acts on
  // M112 as soon as it arrives, even with the command queue full.
  out_.resize(out_pos_);
  out_ += "\nM112\n";
  flight_.clear();
  flight_bytes_ = 0;
  state_ = SenderState::Cancelled;
}

void Sender::fail(std::string message) {
  if (state_ == SenderState::Failed) return;
  state_ = SenderState::Failed;
  failure_ = std::move(message);
}

std::string Sender::describe(const Position& p) const {
  if (p.number <= 0) return "none (no line was acknowledged)";
  if (p.source_line == 0) return fmt::format("N{}", p.number);
  if (p.layer <= 0) return fmt::format("line {} of the input (start code, before layer 1)", p.source_line);
  return fmt::format("line {} of the input (layer {})", p.source_line, p.layer);
}

}  // namespace gcode::serial
