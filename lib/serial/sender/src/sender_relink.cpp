// After the port went away and came back (gc-send --reconnect): the
// sender's side of the Relocator (relocator.hpp), which decides each step.

#include <fmt/format.h>

#include "gcode/serial/protocol/printer_report.hpp"
#include "gcode/serial/protocol/protocol.hpp"
#include "gcode/serial/sender/sender.hpp"

namespace gcode::serial {

void Sender::link_lost(double now) {
  if (finished()) return;
  relocator_.lost(now);
  // Bytes not written yet never reach the printer; what it has of the rest
  // it says after the reconnect.
  out_total_ -= out_.size() - out_pos_;
  out_.clear();
  out_pos_ = 0;
  flight_.clear();
  idle_hint_ = false;
}

void Sender::link_back(double now) {
  if (relocator_.phase() != Relocator::Phase::Down || finished()) return;
  if (handshaking()) {
    // Dropped while M110 or M115 waited for its answer: no numbered line
    // went out since, so there is nothing to locate; the questions start
    // again (the probe's refusal would pass for their answers).
    relocator_.forget();
    log(LogLevel::Warning, 0, "the port came back during the handshake (M110, M115); asking again");
    begin_handshake(now);
    return;
  }
  if (!config_.firmware->checks_line_numbers) {
    // (A mis-numbered line would simply run on Klipper.)
    fail(fmt::format("the port came back, but {} does not number lines: it cannot say which line it took last; "
                     "last acknowledged: {}",
                     config_.firmware->name, describe(last_acked_)));
    return;
  }
  std::string probe;
  append_numbered_line(probe, relocator_.probe(now, highest_sent_), kProbe);
  out_ += probe;
  out_total_ += probe.size();
  if (trace_) log(LogLevel::Trace, 0, fmt::format("-> {}", std::string_view(probe).substr(0, probe.size() - 1)));
}

// The printer refused the probe and asked for line `expected`.
void Sender::relocate(long long expected, double now) {
  const long long last = expected - 1;
  switch (relocator_.refused(expected, last_acked_.number, highest_sent_, now)) {
    case Relocator::Refusal::Restarted:
      printer_reset("its line numbers were back at 0 when its port came back", now);
      return;
    case Relocator::Refusal::Impossible:
      fail(fmt::format("after the reconnect the printer says its last line is N{}, but N{} was acknowledged and N{} "
                     "sent last; not going on",
                       last, last_acked_.number, highest_sent_));
      return;
    case Relocator::Refusal::Took: break;
  }
  for (long long n = last_acked_.number + 1; n <= last; ++n) {
    const Slot& s = slot(n);
    if (s.source_line != 0) {
      last_acked_.source_line = s.source_line;
      last_acked_.layer = s.layer;
    }
  }
  last_acked_.number = last;
  next_send_ = last + 1;
  log(LogLevel::Info, 0, fmt::format("the printer took every line up to N{} ({}); asking where it stands (M114)", last,
                                     describe(last_acked_)));
}

// The answer to M114 (false: `text` is not one).
bool Sender::check_position(std::string_view text, double now) {
  std::optional<PositionReport> report = parse_position_report(text);
  if (!report) return false;
  static constexpr const char* kAxes[] = {"X", "Y", "Z"};
  const long long line = relocator_.line();
  if (line > 0) {
    const Slot& s = slot(line);
    if (const int a = axis_off(*report, s.at, 0.01); a >= 0) {
      const auto i = static_cast<std::size_t>(a);
      fail(fmt::format("after the reconnect the printer stands at {}{:.3f}, but N{} ({}) left it at {}{:.3f}: it did not "
                       "keep its state; not going on",
                       kAxes[i], report->axis[i], line, describe(last_acked_), kAxes[i], s.at[i]));
      return true;
    }
  }
  relocator_.placed();
  last_rx_ = now;
  log(LogLevel::Warning, 0,
      fmt::format("the printer ran on and stands where N{} left it; going on from N{}", line, next_send_));
  return true;
}

// An "ok" while the printer is located (Relocator::ok).
void Sender::relink_ok(double now) {
  resend_.take_rejected_ok();
  switch (relocator_.ok()) {
    case Relocator::Ok::Done: fill(now); break;
    case Relocator::Ok::AskPosition: send_unnumbered("M114"); break;
    case Relocator::Ok::Wait: break;
  }
}

}  // namespace gcode::serial
