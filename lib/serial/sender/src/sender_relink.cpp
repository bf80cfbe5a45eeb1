// After the port went away and came back (gc-send --reconnect): where the
// printer is. Marlin's "ok" means queued, not done, and answers sent while
// the link was gone were lost, so the sender cannot know which lines the
// printer took; it asks. A line with a number the printer cannot expect is
// refused with "Last Line: n" (every line up to n was taken, and a board
// that kept its power runs them all), then M114 says where it stands, which
// must be where line n left it.

#include <fmt/format.h>

#include "gcode/serial/protocol/printer_report.hpp"
#include "gcode/serial/protocol/protocol.hpp"
#include "gcode/serial/sender/sender.hpp"

namespace gcode::serial {

void Sender::link_lost(double now) {
  if (finished()) return;
  relink_ = Relink::Down;
  relink_since_ = now;
  // Bytes not written yet never reach the printer; what it has of the rest
  // it says after the reconnect.
  out_total_ -= out_.size() - out_pos_;
  out_.clear();
  out_pos_ = 0;
  flight_.clear();
  idle_hint_ = false;
}

void Sender::link_back(double now) {
  if (relink_ != Relink::Down || finished()) return;
  if (handshaking()) {
    // Dropped while M110 or M115 waited for its answer: no numbered line
    // went out since, so there is nothing to locate; the questions start
    // again (the probe's refusal would pass for their answers).
    relink_ = Relink::None;
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
  relink_ = Relink::Probing;
  relink_since_ = now;
  position_asked_ = false;
  // No printer can expect this number: the highest sent is at most one
  // past its last line.
  std::string probe;
  append_numbered_line(probe, highest_sent_ + 2, kProbe);
  out_ += probe;
  out_total_ += probe.size();
  if (trace_) log(LogLevel::Trace, 0, fmt::format("-> {}", std::string_view(probe).substr(0, probe.size() - 1)));
}

// The printer refused the probe and asked for line `expected`: it has every
// line before it.
void Sender::relocate(long long expected, double now) {
  const long long last = expected - 1;
  if (last == 0 && highest_sent_ > 0) {
    // It restarted while the port was away, its greeting lost with the
    // link: a reset like any other.
    printer_reset("its line numbers were back at 0 when its port came back", now);
    return;
  }
  if (last < last_acked_.number || last > highest_sent_) {
    fail(fmt::format("after the reconnect the printer says its last line is N{}, but N{} was acknowledged and N{} "
                     "sent last; not going on",
                     last, last_acked_.number, highest_sent_));
    return;
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
  relink_ = Relink::Locating;
  relink_line_ = last;
  relink_since_ = now;
  log(LogLevel::Info, 0, fmt::format("the printer took every line up to N{} ({}); asking where it stands (M114)", last,
                                     describe(last_acked_)));
}

// The answer to M114 (false: `text` is not one).
bool Sender::check_position(std::string_view text, double now) {
  std::optional<PositionReport> report = parse_position_report(text);
  if (!report) return false;
  static constexpr const char* kAxes[] = {"X", "Y", "Z"};
  if (relink_line_ > 0) {
    const Slot& s = slot(relink_line_);
    if (const int a = axis_off(*report, s.at, 0.01); a >= 0) {
      const auto i = static_cast<std::size_t>(a);
      fail(fmt::format("after the reconnect the printer stands at {}{:.3f}, but N{} ({}) left it at {}{:.3f}: it did not "
                       "keep its state; not going on",
                       kAxes[i], report->axis[i], relink_line_, describe(last_acked_), kAxes[i], s.at[i]));
      return true;
    }
  }
  relink_ = Relink::Finishing;
  last_rx_ = now;
  log(LogLevel::Warning, 0,
      fmt::format("the printer ran on and stands where N{} left it; going on from N{}", relink_line_, next_send_));
  return true;
}

// An "ok" while the printer is located. The first is the refused probe's:
// the printer's buffer is empty now, M114 goes out (counted by no ledger:
// its answer is told apart by its text). Until that answer come the oks of
// lines the printer had queued before the probe (all of them up to its last
// line, known to be taken); after it, M114's own ok, and sending goes on.
void Sender::relink_ok(double now) {
  resend_.take_rejected_ok();
  if (relink_ == Relink::Finishing) {
    relink_ = Relink::None;
    fill(now);
    return;
  }
  if (!position_asked_) {
    position_asked_ = true;
    send_unnumbered("M114");
  }
}

}  // namespace gcode::serial
