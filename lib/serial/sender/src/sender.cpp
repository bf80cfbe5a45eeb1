#include "gcode/serial/sender/sender.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "gcode/core/line.hpp"

namespace gcode::serial {

EstimatorOptions sender_estimator_options() {
  EstimatorOptions o;
  o.heat_time = false;  // heating has no bound here: keepalives tell
  o.home_time = 0;
  o.lookahead = 16;     // Marlin's planner: times are final 16 moves later
  return o;
}

Sender::Sender(const SenderConfig& config, Logger log)
    : config_(config),
      log_(std::move(log)),
      flow_(config.flow, config.queue, config.rx_buffer),
      handshake_(config.timeout),
      clock_(config.link_bytes_per_second, config.time_scale, config.planner_blocks),
      estimator_(sender_estimator_options(), this),
      ring_(2048) {}

void Sender::log(LogLevel level, std::uint64_t input_line, std::string_view message) const {
  if (log_) log_(level, input_line, message);
}

void Sender::start(double now) {
  last_rx_ = last_any_rx_ = now;
  if (config_.handshake || handshake_.resumed()) {
    begin_handshake(now);
  } else {
    state_ = SenderState::Printing;
    fill(now);
  }
}

// The questions before the first line; again after a reset
// (restart_handshake) or a link drop that cut them short
// (sender_relink.cpp).
void Sender::begin_handshake(double now) {
  state_ = SenderState::Handshake;
  send_unnumbered(handshake_.begin(now));
}

void Sender::continue_from(long long next, const MachineState& printer, const ResumeTrack& track,
                           std::uint64_t source_line, int layer) {
  next_number_ = next_send_ = next;
  highest_sent_ = journaled_ = next - 1;
  resent_above_highest_ = 0;
  last_acked_.number = next - 1;
  machine_ = printer;
  handshake_.resume_running_printer();
  first_held_ = next;
  last_enqueued_ = next - 1;
  track_ = track;
  // The printer kept running: it drained what it took, so every command up
  // to next - 1 ran.
  recovery_.hold_base(next - 1, printer, track, source_line, layer);
}

void Sender::grow_ring() {
  std::vector<Slot> bigger(ring_.size() * 2);
  long long from = std::max<long long>(1, next_send_ - kHistory);
  for (long long n = from; n < next_number_; ++n)
    bigger[static_cast<std::size_t>(n) & (bigger.size() - 1)] = std::move(slot(n));
  ring_.swap(bigger);
}

void Sender::on_time(std::int64_t tag, double seconds) {
  // Final times arrive up to 16 moves after the line was queued, well within
  // the history; anything older is no longer needed. Tags rise with the
  // numbers (a command taken back and numbered again gets a new one), and
  // a line of the sender's own carries none.
  const auto wanted = static_cast<std::uint64_t>(tag);
  const long long oldest = std::max<long long>(1, next_send_ - kHistory);
  long long n = next_number_ - 1;
  while (n >= oldest && (slot(n).own != InFlight::Own::None || slot(n).tag > wanted)) --n;
  if (n < oldest || slot(n).tag != wanted) return;
  Slot& s = slot(n);
  if (!s.motion_final) {
    s.motion = 0;
    s.motion_final = true;
  }
  s.motion += seconds;
}

void Sender::submit(std::string_view command, std::uint64_t source_line, int layer) {
  if (command.empty() || cancelled_ || input_done_) return;
  LineCheck check = check_line(command, next_number_, config_.max_line);
  if (check.problem == LineProblem::Shortened) {
    ++stats_.shortened;
    log(LogLevel::Warning, source_line, serial::describe(check, config_.max_line));
    command = check.command;
  } else if (check.problem != LineProblem::None) {
    std::string why = serial::describe(check, config_.max_line);
    if (config_.skip_bad_lines) {
      ++stats_.skipped;
      log(LogLevel::Warning, source_line, why + "; left out (--skip-bad-lines)");
      return;
    }
    refuse(source_line, std::move(why));
    return;
  }
  enqueue(command, source_line, layer);
}

void Sender::refuse(std::uint64_t source_line, std::string why) {
  // Everything before the line is printed; nothing from it on.
  refusal_ = fmt::format("line {}: {}; not sent: printing stopped before it (--skip-bad-lines leaves such lines out)",
                         source_line, why);
  input_done_ = true;
  estimator_.finish();
  if (next_number_ == 1) fail(refusal_);  // nothing before it to print
}

void Sender::enqueue(std::string_view command, std::uint64_t source_line, int layer, bool closing) {
  if (next_number_ - std::max<long long>(1, next_send_ - kHistory) >= static_cast<long long>(ring_.size())) grow_ring();
  Slot& s = slot(next_number_);
  s.wire.clear();  // keeps its capacity: no allocation per line once warm
  append_numbered_line(s.wire, next_number_, command);
  s.source_line = source_line;
  s.layer = layer;
  Line line = Line::parse(command);
  s.unbounded = config_.firmware->is_unbounded(line);
  s.silent_wait = config_.firmware->waits_silently(line);
  s.long_running = config_.firmware->is_long_running(line);
  s.temperature_query = line.is_m(105);
  s.homes = is_homing_command(line);
  Move move = machine_.apply(line);
  s.at = {machine_.position[kX], machine_.position[kY], machine_.position[kZ]};
  track(s, line, move);
  s.closing = closing;
  s.own = InFlight::Own::None;
  // Until the estimator's time is final (16 moves later), length / feed rate.
  s.motion = 0;
  s.motion_final = false;
  double length = move.length > 0 ? move.length : std::fabs(move.filament);
  bool motion_command = move.kind == MoveKind::Linear || move.kind == MoveKind::Arc;
  s.move = motion_command && !move.ignored && length > 0;
  // "G1 F1200" moves nothing and is answered at once.
  s.instant = !s.move && (motion_command || config_.firmware->is_instant(line));
  s.nominal = s.move && move.feedrate > 0 ? length / (move.feedrate / 60) : 0;
  s.motion = s.nominal;
  s.tag = next_tag_++;
  estimator_.set_tag(static_cast<std::int64_t>(s.tag));
  ++next_number_;
  estimator_.add(line, move);
}

std::size_t Sender::withdraw_unsent(std::size_t max, const MachineState& before, std::vector<std::string>& commands) {
  if (final_queued_ || cancelled_) return 0;
  std::size_t n = std::min(max, pending());
  if (n == 0) return 0;
  for (long long k = next_number_ - static_cast<long long>(n); k < next_number_; ++k)
    commands.emplace_back(command_of_numbered(slot(k).wire));
  next_number_ -= static_cast<long long>(n);
  if (next_number_ <= highest_sent_ + 1) resent_above_highest_ = 0;  // (none of them waits now)
  // The estimator has seen them: their times are only estimates anyway.
  machine_ = before;
  took_back();
  return n;
}

std::size_t Sender::discard_unsent() {
  if (final_queued_ || cancelled_) return 0;
  std::size_t n = pending();
  next_number_ = next_send_;
  if (next_number_ <= highest_sent_ + 1) resent_above_highest_ = 0;
  took_back();
  return n;
}

void Sender::end_of_input() {
  if (input_done_) return;
  input_done_ = true;
  estimator_.finish();
  if (next_number_ == 1 && !cancelled_)
    fail(stats_.skipped > 0 ? fmt::format("nothing was printed: all {} commands of the input were left out",
                                          stats_.skipped)
                            : std::string("nothing was printed: the input has no G-code command"));
}

void Sender::reopen_input() {
  if (cancelled_ || !refusal_.empty() || finished()) return;
  input_done_ = false;
}

void Sender::pump(double now) {
  fill(now);
  check_done(now);
}

void Sender::push_flight(long long number, std::size_t bytes, bool temperature_query, InFlight::Own own) {
  out_total_ += bytes;
  std::uint8_t marks = 0;
  if (number > 0 && own == InFlight::Own::None) {
    const Slot& s = slot(number);
    marks = static_cast<std::uint8_t>((s.long_running ? InFlight::kLongRunning : 0) |
                                      (s.unbounded ? InFlight::kUnbounded : 0) |
                                      (s.silent_wait ? InFlight::kSilentWait : 0) | (s.move ? InFlight::kMove : 0));
  }
  flight_.push(number, bytes, temperature_query, out_total_, marks, own);
}

// The handshake's lines (M110, M115) and a reconnect's M114: before the
// numbering is settled, and answered before anything else goes.
void Sender::send_unnumbered(std::string_view command) {
  out_ += command;
  out_ += '\n';
  if (trace_) log(LogLevel::Trace, 0, fmt::format("-> {}", command));
  out_total_ += command.size() + 1;
}

// The commands numbered but not sent yet (a move the pacer holds, a block
// of the control's) move up one number; their journal records are written
// when they go out, so nothing but the estimator's tags knew the old ones.
long long Sender::make_room_for_own() {
  const long long k = next_send_;
  if (next_number_ + 1 - std::max<long long>(1, next_send_ - kHistory) >= static_cast<long long>(ring_.size()))
    grow_ring();
  const long long prev = k < next_number_ ? slot(k).prev : last_enqueued_;
  for (long long n = next_number_; n > k; --n) {
    Slot& s = slot(n);
    s = std::move(slot(n - 1));
    std::string command(command_of_numbered(s.wire));
    s.wire.clear();
    append_numbered_line(s.wire, n, command);
    if (s.prev >= k) ++s.prev;
  }
  if (last_enqueued_ >= k) ++last_enqueued_;
  ++next_number_;
  // Lines sent already and refused since (a rewind to k): they go out
  // again under their new numbers, and are journaled again so. The highest
  // number on the wire stays what it is (a resend request past it names a
  // line never sent), and the one of them that goes out above it is counted
  // as sent again, not as a new line.
  if (highest_sent_ >= k) ++resent_above_highest_;
  journaled_ = std::min(journaled_, k - 1);
  return prev;
}

// Whether every command waiting to go out still fits the firmware's line
// once moved up one number: N99 becomes N100, and the checksum changes too
// (*9 may become *123), so the line is made anew and measured. Where one
// would not fit, gc-send asks nothing of its own until that command is out.
// (Only when an own line is due, over the few commands that wait.)
bool Sender::room_for_own() {
  for (long long n = next_send_; n < next_number_; ++n) {
    moved_.clear();
    append_numbered_line(moved_, n + 1, command_of_numbered(slot(n).wire));
    if (moved_.size() > config_.max_line) return false;
  }
  return true;
}

void Sender::send_own(InFlight::Own kind, double now) {
  const long long k = next_send_;
  const long long prev = make_room_for_own();
  Slot& s = slot(k);
  const PrintStep& before = prev > 0 && (in_history(prev) || recovery_.is_base(prev)) ? held(prev) : PrintStep();
  s.source_line = before.source_line;
  s.layer = before.layer;
  s.at = before.at;
  s.after = before.after;
  s.track = before.track;
  s.prev = prev;
  // Inside a way back after a reset, an own line is of it: a resume that
  // finds the printer took it makes the way back again.
  s.restore = before.restore;
  s.long_running = s.unbounded = s.silent_wait = s.move = s.drains = s.closing = s.homes = false;
  s.temperature_query = kind == InFlight::Own::Question;
  // M105 is answered at once; the probe waits for a planner block.
  s.instant = kind == InFlight::Own::Question;
  s.motion = s.nominal = 0;
  s.motion_final = true;
  s.own = kind;
  s.tag = 0;
  s.wire.clear();
  append_numbered_line(s.wire, k, kind == InFlight::Own::Question ? kProbe : kPaceProbe);
  out_ += s.wire;
  if (trace_)
    log(LogLevel::Trace, 0, fmt::format("-> {} @{:.6f}{}", std::string_view(s.wire).substr(0, s.wire.size() - 1), now,
                                        kind == InFlight::Own::PaceProbe ? " (pace probe)" : ""));
  push_flight(k, s.wire.size(), s.temperature_query, kind);
  journal_first_send(k);
  highest_sent_ = std::max(highest_sent_, k);
  if (flight_.lines() == 1) last_rx_ = std::max(last_rx_, now);
  ++next_send_;
}

// The journal's record of a line, written as it first goes out (before its
// bytes can reach the port): a line of the sender's own repeats the point
// of the command before it.
void Sender::journal_first_send(long long number) {
  if (number <= journaled_) return;
  journaled_ = number;
  if (!on_numbered_) return;
  const Slot& s = slot(number);
  on_numbered_({number, s.source_line, s.layer, &s.after, &s.track, s.restore, s.closing, s.drains,
                s.own != InFlight::Own::None});
}

void Sender::written(std::size_t n, double now) {
  out_pos_ += n;
  stats_.bytes += n;
  if (out_pos_ == out_.size()) {
    out_.clear();
    out_pos_ = 0;
  }
  if (n == 0) return;
  written_total_ += n;
  clock_.written(n, now);
  flight_.written(written_total_, [this](std::size_t after) { return clock_.arrival_of(after); });
  resend_.heard(now);
}

bool Sender::settled(double now) const {
  // An M105 of ours still unanswered once every line is acknowledged was
  // lost: the printer runs it as soon as it reaches the head of its queue.
  return output().empty() && !lines_in_flight() && resend_.quiet(now, last_any_rx_);
}

void Sender::fill(double now) {
  pacer_.clear_wake();
  if (state_ != SenderState::Printing || paused_ || printer_paused_ || cancelled_ || relocator_.active()) return;
  if (resend_.settling()) {
    if (!settled(now)) return;
    resend_.settled();
  }
  // Room is kept in the printer's buffer for an M105, which goes out
  // whenever an answer is overdue.
  std::size_t reserve = flight_.asking() ? 0 : own_line_bytes(kProbe);
  for (;;) {
    if (input_done_ && !final_queued_ && next_send_ == next_number_ && config_.finish_with_m400 && next_number_ > 1) {
      final_queued_ = true;
      enqueue("M400", 0, last_acked_.layer, true);
    }
    if (next_send_ >= next_number_) break;
    const Slot& s = slot(next_send_);
    // Our M105s hold bytes of the printer's buffer but no place in its
    // queue for long: it answers them as soon as they are read.
    if (!flow_.may_send(flight_.lines(), flight_.bytes() + reserve, s.wire.size())) break;
    if (pacing() && s.move && paced(now)) {
      pace_probe(now, reserve);
      break;
    }
    out_ += s.wire;
    if (trace_)
      log(LogLevel::Trace, 0, fmt::format("-> {} @{:.6f}", std::string_view(s.wire).substr(0, s.wire.size() - 1), now));
    push_flight(next_send_, s.wire.size(), s.temperature_query, s.own);
    idle_hint_ = false;  // "wait" was about what went before
    const bool probe_ahead = pacing() && s.move && pacer_.probe_ahead(clock_.planner_blocks());
    journal_first_send(next_send_);
    if (next_send_ > highest_sent_ && resent_above_highest_ > 0) {
      highest_sent_ = next_send_;
      --resent_above_highest_;
      ++stats_.resent_lines;
    } else if (next_send_ > highest_sent_) {
      highest_sent_ = next_send_;
      ++stats_.lines;
      stats_.payload_bytes += s.wire.size();
      if (stats_.print_start < 0) stats_.print_start = now;
    } else {
      ++stats_.resent_lines;
    }
    if (flight_.lines() == 1) last_rx_ = std::max(last_rx_, now);  // the timeout runs from the first line in flight
    ++next_send_;
    // (Numbered after the move, as it goes after it.)
    if (probe_ahead) pace_probe(now, reserve);
  }
  check_done(now);
}

void Sender::check_done(double now) {
  // Done when every line is acknowledged (an M105 of ours may still be out).
  if (state_ == SenderState::Printing && !relocator_.active() && input_done_ &&
      (final_queued_ || !config_.finish_with_m400) &&
      next_send_ == next_number_ && !lines_in_flight() && !resend_.settling() && next_number_ > 1) {
    if (!refusal_.empty()) {
      fail(refusal_);
    } else if (!lost_.empty()) {
      fail(lost_);  // its safe end went out
    } else {
      state_ = SenderState::Done;
    }
    stats_.print_end = now;
  }
  if (cancelled_ && state_ != SenderState::Failed && flight_.empty()) {
    if (lost_.empty()) {
      state_ = SenderState::Cancelled;
    } else {
      fail(lost_);
    }
  }
}

void Sender::acknowledge_front(double now, int planner_free) {
  const InFlight::Entry f = flight_.pop_front();
  if (f.own != InFlight::Own::None) {
    clock_.answered(0, now);
    if (f.own == InFlight::Own::PaceProbe && pacing())
      pacer_.probe_answered(now, f.arrival == InFlight::kNotArrived ? Pacer::kUnknown : f.arrival,
                            clock_.planner_blocks());
    if (f.number > last_acked_.number) {
      last_acked_.number = f.number;
      if (on_acknowledged_) on_acknowledged_(f.number);
    }
    return;
  }
  const Slot& s = slot(f.number);
  homing_.acknowledged(s.homes);
  clock_.answered(s.move ? s.motion : 0, now, s.move ? s.nominal : 0);
  if (s.move) queued_end_ = std::max(queued_end_, now) + s.motion / config_.time_scale;
  planned(s, f, now, planner_free);
  if (f.number > last_acked_.number) {
    last_acked_.number = f.number;
    if (on_acknowledged_) on_acknowledged_(f.number);
    if (s.source_line != 0) {
      last_acked_.source_line = s.source_line;
      last_acked_.layer = s.layer;
    }
  }
}

void Sender::acknowledge_through(std::size_t index, double now, int planner_free) {
  // ADVANCED_OK's P is the planner's as the last of them was answered.
  for (std::size_t i = 0; i <= index; ++i) acknowledge_front(now, i == index ? planner_free : -1);
}

void Sender::on_ok(const Response& r, double now) {
  ++stats_.oks;
  timeouts_in_row_ = 0;
  last_rx_ = now;
  flow_.on_ok(r);
  if (r.planner_free > learnt_planner_ && flow_.ok_numbers_acknowledge()) {
    // The planner has at least P blocks (all of them free when it is empty).
    // The largest P seen replaces the assumed size: a size too small only
    // makes the sender wait longer for an answer.
    learnt_planner_ = r.planner_free;
    clock_.set_planner_blocks(learnt_planner_);
  }
  if (answers_handshake(r, now)) return;
  // Marlin answers a rejected line with Error, Resend and "ok": that ok
  // belongs to the rejected line, which already left the flight list.
  if (relocator_.phase() == Relocator::Phase::Locating || relocator_.phase() == Relocator::Phase::Finishing) {
    relink_ok(now);
    return;
  }
  if (resend_.take_rejected_ok()) return;
  probes_.answered();
  idle_hint_ = false;
  // The answer of a question taken with an earlier one's (InFlight::Answer::
  // written_off): taken for a newer question, it would acknowledge lines
  // the printer has not run yet (a firmware whose oks wait, as Klipper's
  // while about 1 s of motion is queued, draws several questions in a row).
  if (r.has_temperature && written_off_ > 0) {
    --written_off_;
    ++stats_.stray_oks;
    fill(now);
    return;
  }
  const InFlight::Answer answer = flight_.answer_to(r, flow_.ok_numbers_acknowledge());
  written_off_ += answer.written_off;
  switch (answer.kind) {
    case InFlight::Answer::Kind::Stray: ++stats_.stray_oks; break;
    case InFlight::Answer::Kind::Through:
      acknowledge_through(answer.index, now, flow_.ok_numbers_acknowledge() ? r.planner_free : -1);
      break;
    case InFlight::Answer::Kind::Question:
      flight_.erase(answer.index);
      clock_.answered(0, now);
      break;
  }
  if (flight_.empty() && stats_.print_start >= 0) stats_.print_end = now;
  fill(now);
}

// An "ok" during the handshake: M110's (then M115 goes out), or M115's.
bool Sender::answers_handshake(const Response& r, double now) {
  if (!handshaking()) return false;
  switch (handshake_.ok(now)) {
    case Handshake::Answer::AskCapabilities: send_unnumbered(handshake_.question()); break;
    case Handshake::Answer::Capabilities:
      // Klipper answers M115 on its ok line.
      if (r.text.find("FIRMWARE_NAME:") != std::string_view::npos) on_capability(r.text);
      break;
    case Handshake::Answer::Extra: ++stats_.stray_oks; break;
  }
  return true;
}

void Sender::on_resend(long long n, double now) {
  resend_.expect_rejected_ok();
  // A bad line empties Marlin's receive buffer: our questions behind it are
  // gone, so are the answers written off with them.
  written_off_ = 0;
  idle_hint_ = false;
  if (state_ != SenderState::Printing) return;
  if (relocator_.phase() == Relocator::Phase::Probing) {
    relocate(n, now);
    return;
  }
  if (n < 1 || n > highest_sent_ + 1 || n > next_number_) {
    // A line never sent: nothing to rewind to (its "ok" still follows).
    ++stats_.ignored_resends;
    return;
  }
  if (n < std::max<long long>(1, next_send_ - kHistory)) {
    // Line 1 long after it was sent: the printer's numbering is back at 0,
    // it restarted and its greeting did not reach us.
    if (n == 1) {
      printer_reset("its line numbers are back at 0: it asked for line 1", now);
      return;
    }
    fail(fmt::format("the printer asked to resend line {}, which is no longer in the history (sent up to {})", n,
                     highest_sent_));
    return;
  }
  // A question of ours numbered n, sent while the rewind settled (after the
  // stale lines): a request for n now is its own refusal, not a stale one.
  if (resend_.settling() && std::any_of(flight_.begin(), flight_.end(), [n](const InFlight::Entry& e) {
        return e.own != InFlight::Own::None && e.number >= n;
      }))
    resend_.settled();
  switch (resend_.request(n, config_.max_resends)) {
    case ResendState::Verdict::Repeat: ++stats_.duplicate_resends; return;
    case ResendState::Verdict::TooMany:
      fail(fmt::format("the printer asked for line {} {} times; giving up", n, resend_.count()));
      return;
    case ResendState::Verdict::Rewind: break;
  }
  ++stats_.resend_requests;
  // "Resend: n" says the printer has every line before n and nothing after:
  // whatever of ours follows line n-1 in the flight list (lines from n on
  // and any M105 sent after them) is lost or will be rejected.
  const std::size_t stale_bytes = flight_.drop_from(n);
  next_send_ = n;
  // Wait until every line before n is acknowledged (the printer's queue is
  // then empty and it reads each arriving byte at once) and the link has
  // been quiet long enough for the stale lines to reach it and be rejected;
  // their requests for n are repeats, and their rejections would empty the
  // printer's buffer again, taking an early copy of line n with it.
  resend_.rewound(n, now, clock_.quiet(stale_bytes + output().size()));
  log(LogLevel::Info, slot(n).source_line, fmt::format("resend from {}", describe({n, slot(n).source_line, slot(n).layer})));
}

void Sender::set_link(double bytes_per_second, double time_scale) {
  config_.link_bytes_per_second = bytes_per_second;
  config_.time_scale = time_scale;
  clock_.set_link(bytes_per_second, time_scale);
}

void Sender::on_capability(std::string_view text) {
  const std::size_t max_line = firmware_.max_line;
  const CapabilityLine said = read_capability(text, firmware_);
  // A simulated printer's link runs at its own pace, not the port's.
  if (said.names_firmware && firmware_.time_scale > 0 && firmware_.baud > 0)
    set_link(firmware_.baud / 10 * firmware_.time_scale, firmware_.time_scale);
  if (said.max_line) {
    // Only from the handshake, and only if the lines already checked and
    // waiting to go out (a reset's way back and its re-run) still fit.
    if (state_ == SenderState::Printing || !waiting_lines_fit(firmware_.max_line)) {
      firmware_.max_line = max_line;
    } else if (config_.max_line_from_firmware) {
      config_.max_line = firmware_.max_line;
    }
  }
  if (firmware_.advanced_ok && config_.firmware->advanced_ok_possible) flow_.firmware_has_advanced_ok();
  if (said.names_firmware) detect_flavour();
}

bool Sender::waiting_lines_fit(std::size_t max_line) const {
  for (long long n = next_send_; n < next_number_; ++n)
    if (slot(n).wire.size() > max_line) return false;  // (wire: with its newline, as the limit counts)
  return true;
}

// The firmware named in the answer to M115 picks the description, before
// any line of the input is taken (they are classified by it).
void Sender::detect_flavour() {
  const FirmwareFlavor* found = find_firmware_by_report(firmware_.name);
  if (config_.firmware_from_report && found != nullptr && found != config_.firmware) {
    config_.firmware = found;
    log(LogLevel::Info, 0, fmt::format("firmware: {} (flavour {})", firmware_.name, found->name));
  }
  // Said once, whether the flavour was detected now or set in the config.
  if (config_.pace && config_.firmware->ok_when_queued && !pacing_off_said_) {
    pacing_off_said_ = true;
    log(LogLevel::Info, 0, "pacing off: this firmware queues seconds of motion before its answers wait");
  }
}

void Sender::on_line(std::string_view text, double now) {
  if (trace_) log(LogLevel::Trace, 0, fmt::format("<- {} @{:.6f}", text, now));
  Response r = parse_response(text);
  // Marlin's "wait" (NO_TIMEOUTS) says the printer is idle with an empty
  // buffer: the link is as quiet as it gets (the handshake's quiet start and
  // a resend's settling must not wait for it to stop).
  if (r.kind != ResponseKind::Wait) {
    last_any_rx_ = now;
    resend_.heard(now);
  }
  note_temperatures(r, text);
  if (relocator_.position_due() && check_position(text, now)) return;
  if (r.kind != ResponseKind::Ok && r.kind != ResponseKind::Resend && r.kind != ResponseKind::Empty)
    resend_.other_answer();
  switch (r.kind) {
    case ResponseKind::Empty: break;
    case ResponseKind::Ok: on_ok(r, now); break;
    case ResponseKind::Resend:
      last_rx_ = now;
      timeouts_in_row_ = 0;
      on_resend(r.line, now);
      break;
    case ResponseKind::Error: on_error(r, now); break;
    case ResponseKind::Busy:
      ++stats_.busy;
      timeouts_in_row_ = 0;
      last_rx_ = now;
      last_busy_ = now;
      clock_.keepalive(now);
      pacer_.interrupted();
      break;
    case ResponseKind::Action: on_action(r.text); break;
    case ResponseKind::Temperature:
      // Heating waits (M109/M190) report temperatures instead of "busy".
      if (long_command_in_flight()) {
        last_rx_ = now;
        clock_.keepalive(now);
        pacer_.interrupted();
      }
      break;
    case ResponseKind::Capability: on_capability(r.text); break;
    case ResponseKind::Start: on_start(r.text, now); break;
    case ResponseKind::Echo:
      if (r.unknown_command) {
        // Marlin and Klipper answer an unknown command so, with its ok: the
        // print goes on without it.
        ++stats_.unknown_commands;
        log(LogLevel::Warning, 0, fmt::format("the printer did not take a command: {}", r.text));
      } else if (r.lost_number) {
        log(LogLevel::Info, 0, fmt::format("printer: {} (a line that lost its N on the way: it is sent again)", r.text));
      } else {
        log(LogLevel::Info, 0, fmt::format("printer: {}", r.text));
        // Marlin refuses a move so when it does not know where it is.
        if (std::string why = homing_.message(r.text); !why.empty()) print_lost(std::move(why));
      }
      // Marlin's boot after the reset pin ("start" may have been lost).
      if (is_reset_note(r.text)) on_start(r.text, now);
      break;
    case ResponseKind::Wait:
      // Marlin (NO_TIMEOUTS) and Repetier say "wait" when their queue and
      // buffer are empty: a line still believed in flight lost its answer.
      if (state_ == SenderState::Printing && !flight_.empty() && output().empty()) idle_hint_ = true;
      break;
    case ResponseKind::Unknown:
      ++stats_.unknown;
      log(LogLevel::Info, 0, fmt::format("printer: {}", r.text));
      break;
  }
  fill(now);
  check_done(now);
}

// The last temperature report, for the progress ("T:205.00 /205.00 B:60.00 /60.00").
void Sender::note_temperatures(const Response& r, std::string_view text) {
  if (!(r.kind == ResponseKind::Temperature || r.has_temperature) || text.find_first_of("TB") == std::string_view::npos)
    return;
  std::string_view t = text.substr(text.find_first_of("TB"));
  temperatures_.assign(t.substr(0, t.find(" @")));  // without the heater powers
  for (char& c : temperatures_)
    if (c == '"' || c == '\\' || static_cast<unsigned char>(c) < 0x20) c = ' ';  // kept JSON-safe
}

void Sender::on_error(const Response& r, double now) {
  ++stats_.errors;
  last_rx_ = now;
  if (r.error == ErrorClass::Fatal) {
    fail(fmt::format("the printer reported a fatal error: {}; last acknowledged: {}", r.text, describe(last_acked_)));
  } else {
    log(r.error == ErrorClass::Recoverable ? LogLevel::Warning : LogLevel::Info, 0,
        fmt::format("printer error: {}", r.text));
    if (r.error != ErrorClass::Recoverable) return;
    const Slot* oldest = oldest_file_line();
    std::string why = homing_.error(r.text, oldest != nullptr ? command_of_numbered(oldest->wire) : std::string_view(),
                                    oldest != nullptr && oldest->homes);
    if (!why.empty()) print_lost(std::move(why));
  }
}

const Sender::Slot* Sender::oldest_file_line() const {
  if (flight_.empty() || flight_.front().own != InFlight::Own::None || flight_.front().number <= 0) return nullptr;
  return &slot(flight_.front().number);
}

// The printer cannot put the file's moves where they belong: the rest of
// the file is not sent; what goes out is the handler's safe end.
void Sender::print_lost(std::string why) {
  if (!lost_.empty() || state_ != SenderState::Printing || cancelled_) return;
  lost_ = std::move(why);
  if (on_lost_) {
    on_lost_(lost_);  // (it says so, with where the print stopped)
  } else {
    log(LogLevel::Warning, 0, lost_ + "; the print stops");
    cancel();
  }
}

// The printer's //action: (its own pause button, with host actions). Without
// a handler a pause holds sending until the resume.
void Sender::on_action(std::string_view action) {
  log(LogLevel::Warning, 0, fmt::format("printer action: {}", action));
  // Prusa's own pause (M601, its knob): it holds every command until it
  // resumes; so does the sender, and a person decides how long that is.
  if (config_.firmware->reports_own_pause && action.rfind("paused", 0) == 0) printer_paused_ = true;
  if (config_.firmware->reports_own_pause && action.rfind("resumed", 0) == 0) {
    printer_paused_ = false;
    last_rx_ = std::max(last_rx_, last_any_rx_);
  }
  if (on_action_) {
    on_action_(action);
    return;
  }
  if (action.rfind("pause", 0) == 0 && action.rfind("paused", 0) != 0) paused_ = true;
  if (action.rfind("resume", 0) == 0 && action.rfind("resumed", 0) != 0) paused_ = false;
  if (action.rfind("cancel", 0) == 0) cancel();
}

// The greeting after a reset: during the handshake, a board that was still
// booting (or a greeting said twice); while printing, a reset that lost
// what the printer had queued: the print goes back to the last command
// that surely ran (sender_reset.cpp).
void Sender::on_start(std::string_view text, double now) {
  if (handshaking() && handshake_.greeted()) {
    send_unnumbered(handshake_.question());
  } else if (state_ == SenderState::Printing || handshaking()) {
    // (Handshaking here: a resume's M115 to a printer that had kept running
    // the print; it holds the print no longer.)
    printer_reset(fmt::format("it said \"{}\"{}", text, relocator_.active() ? " while its port was away" : ""),
                  now);
  }
}

bool Sender::long_command_in_flight() const { return flight_.marked(InFlight::kLongRunning) > 0; }

// Its own pause, or a command waiting for the user without a word (Prusa's
// M600): the printer is healthy however long that takes.
bool Sender::waiting_for_user() const {
  return printer_paused_ || flight_.marked(InFlight::kSilentWait) > 0;
}

// A long command on a firmware that says nothing until it is done
// (Klipper's and RepRapFirmware's G28, G29, G4).
bool Sender::silent_command_in_flight() const {
  if (config_.firmware->busy_keepalive) return false;
  return flight_.marked(InFlight::kUnbounded) > 0;
}

double Sender::current_timeout() const {
  double t = config_.timeout;
  if (long_command_in_flight()) t *= 6;
  if (silent_command_in_flight()) t *= 6;
  if (last_rx_ - last_busy_ < config_.timeout) t *= 2;  // a busy firmware gets more time
  return t;
}

bool Sender::paced(double now) {
  int moves = static_cast<int>(flight_.marked(InFlight::kMove));
  return pacer_.blocked(now, moves, next_send_, clock_.planner_blocks());
}

// Held back by the pacer: a move of no length asks the printer whether its
// planner really is full (pacer.hpp), on a firmware that holds it until it
// has a block free. It holds a place in the printer's queue like a line,
// and is numbered and checksummed like one: a garbled probe is refused and
// sent again, never run as another command (an unnumbered "G1" with one
// bit changed is "E1"; two make it "M1", a wait for the user).
void Sender::pace_probe(double now, std::size_t reserve) {
  if (!config_.firmware->empty_move_waits || flight_.probing() || resend_.settling()) return;
  if (!pacer_.probe_wanted(clock_.planner_blocks())) return;
  if (!flow_.may_send(flight_.lines(), flight_.bytes() + reserve, own_line_bytes(kPaceProbe))) return;
  if (!room_for_own()) return;
  send_own(InFlight::Own::PaceProbe, now);
  ++stats_.pace_probes;
}

// The bytes of a line of the sender's own, numbered next.
std::size_t Sender::own_line_bytes(std::string_view command) const {
  return command.size() + 3 + static_cast<std::size_t>(std::to_string(next_send_).size()) + 4;
}

void Sender::planned(const Slot& s, const InFlight::Entry& f, double now, int planner_free) {
  if (!pacing()) return;
  if (!s.move) {
    pacer_.answered_other(!s.instant);
    return;
  }
  Pacer::Answer a;
  a.number = f.number;
  a.nominal = s.nominal;
  a.now = now;
  a.arrival = f.arrival == InFlight::kNotArrived ? Pacer::kUnknown : f.arrival;
  a.planner_free = planner_free;
  pacer_.answered(a, clock_.planner_blocks(), config_.time_scale);
}

double Sender::overdue_at() const {
  if (flight_.empty() || state_ != SenderState::Printing || waiting_for_user()) return kNever;
  // The answer the sender waits for: the oldest line's, or while an M105 of
  // ours is out behind it, the newest one's (it answers for everything
  // before it). With no line in flight there is nothing to ask about. (A
  // pace probe is a line here: it waits for a block as a move does.)
  std::size_t first = 0;
  while (first < flight_.size() && flight_[first].own == InFlight::Own::Question) ++first;
  if (first == flight_.size()) return kNever;
  std::size_t k = first;
  for (std::size_t i = first; i < flight_.size(); ++i)
    if (flight_[i].own == InFlight::Own::Question) k = i;
  if (flight_[k].arrival == InFlight::kNotArrived) return kNever;
  AnswerClock::Wait wait;
  // (Questions before the first line are left over from before and have no
  // bearing on when it is answered.)
  for (std::size_t j = first; j <= k; ++j) {
    if (flight_[j].own == InFlight::Own::PaceProbe) ++wait.moves;
    if (flight_[j].own != InFlight::Own::None) continue;
    const Slot& s = slot(flight_[j].number);
    wait.unbounded = wait.unbounded || s.unbounded;
    if (s.move) ++wait.moves;
    // A command that is neither a move nor known to answer at once may wait
    // for the planner to empty.
    if (!s.move && !s.instant) wait.empty = true;
    if (j < k) wait.motion += s.motion;
  }
  // Asked already with a long command ahead: it answers when done, and its
  // keepalives or --timeout tell how long that is.
  if (flight_[k].own == InFlight::Own::Question && wait.unbounded) return kNever;
  // A firmware that says nothing during it (Klipper's G28): nothing to learn
  // by asking before --timeout.
  if (wait.unbounded && !config_.firmware->busy_keepalive) return kNever;
  double due = clock_.due(flight_[k].arrival, wait);
  if (config_.firmware->ok_when_queued) {
    // Klipper holds a move's ok until less than about a second of motion is
    // queued: the motion of the moves it answered and of those ahead in
    // flight, less that second (and, as estimates run short, the move's own).
    const InFlight::Entry& e = flight_[k];
    const double own = e.own == InFlight::Own::None && slot(e.number).move ? slot(e.number).motion : 0;
    const double held = std::max(queued_end_ - kQueuedHold / config_.time_scale, e.arrival);
    due = std::max(due, held + (kQueuedHold + wait.motion + own) / config_.time_scale + clock_.margin());
  }
  // A question without an answer (or one that did not fit) waits twice as
  // long as the one before.
  return probes_.when(due, clock_.margin());
}

double Sender::deadline() const {
  if (finished() || relocator_.phase() == Relocator::Phase::Down) return kNever;
  // A printer heating or homing reads no line until it is done, but says
  // it is alive (temperatures, busy): the probe's answer may take that long.
  if (relocator_.active()) return relocator_.deadline(last_any_rx_, config_.timeout);
  if (handshaking()) return handshake_.deadline(last_any_rx_);
  double d = pacer_.wake();
  // (While paused or cancelled nothing is sent again: no timer for it.)
  if (resend_.settling() && !lines_in_flight() && !paused_ && !cancelled_) d = resend_.quiet_at(last_any_rx_);
  if (!flight_.empty()) {
    d = std::min(d, last_rx_ + current_timeout());
    if (idle_hint_ && !flight_.asking() && lines_in_flight()) d = std::min(d, last_any_rx_);
    if (probes_.quick()) d = std::min(d, overdue_at());
  }
  return d;
}

void Sender::probe(double now, bool silent) {
  idle_hint_ = false;
  probes_.asked(now, clock_.margin());  // asked or not, the next question waits longer
  if (silent) {
    ++stats_.timeouts;
    log(LogLevel::Warning, 0, fmt::format("no answer for {:.3g} s; asking with M105", now - last_rx_));
    last_rx_ = now;
  }
  // Earlier questions stay in flight: their answers may still come, and
  // "ok T:" answers the oldest. Each goes out only if it fits into the
  // printer's buffer on top of everything believed in it.
  if (flight_.bytes() + own_line_bytes(kProbe) >= static_cast<std::size_t>(flow_.rx_buffer())) return;
  // After a rewind to n it is numbered n, so it waits until the lines that
  // were behind the bad one have reached the printer and been refused
  // (each empties its buffer, and would take the question with it).
  if (resend_.settling() && !resend_.quiet(now, last_any_rx_)) return;
  if (!room_for_own()) return;
  if (!silent) {
    ++stats_.probes;
    long long n = flight_.empty() ? -1 : flight_.front().number;
    log(LogLevel::Info, n > 0 ? slot(n).source_line : 0,
        n > 0 ? fmt::format("the answer to N{} is overdue; asking with M105", n)
              : std::string("an answer is overdue; asking with M105"));
  }
  ++stats_.polls;
  send_own(InFlight::Own::Question, now);
}

void Sender::on_timer(double now) {
  if (finished()) return;
  if (relocator_.active()) {
    if (relocator_.phase() != Relocator::Phase::Down && now >= relocator_.deadline(last_any_rx_, config_.timeout))
      fail(fmt::format("after the reconnect the printer did not say where it is (silent for {:g} s); last "
                       "acknowledged: {}",
                       config_.timeout, describe(last_acked_)));
    return;
  }
  if (handshaking() && handshake_.finished(now, last_any_rx_)) {
    state_ = SenderState::Printing;
    if (firmware_.advanced_ok) flow_.firmware_has_advanced_ok();
    fill(now);
    return;
  }
  if (handshaking()) {
    handshake_timer(now);
    return;
  }
  if (!flight_.empty() && now >= last_rx_ + current_timeout() && waiting_for_user()) {
    if (!told_user_wait_)
      log(LogLevel::Info, 0, "the printer waits for someone at it (its own pause, M600): no timeout meanwhile");
    told_user_wait_ = true;
    last_rx_ = now;
  } else if (!flight_.empty() && now >= last_rx_ + current_timeout()) {
    if (++timeouts_in_row_ > config_.max_timeouts) {
      ++stats_.timeouts;
      fail(fmt::format("the printer stopped answering ({} timeouts of {:g} s in a row); last acknowledged: {}",
                       timeouts_in_row_ - 1, current_timeout(), describe(last_acked_)));
      return;
    }
    probe(now, true);
  } else if (lines_in_flight() &&
             ((idle_hint_ && !flight_.asking()) || (now >= overdue_at() && probes_.quick()))) {
    probe(now, false);
  }
  fill(now);
}

// M110 or M115 unanswered: asked again, until the timeout.
void Sender::handshake_timer(double now) {
  switch (handshake_.due(now)) {
    case Handshake::Due::Wait: break;
    case Handshake::Due::AskAgain: send_unnumbered(handshake_.question()); break;
    case Handshake::Due::WithoutCapabilities:
      state_ = SenderState::Printing;
      fill(now);
      break;
    case Handshake::Due::NoAnswer:
      fail(fmt::format("no answer from the printer within {} s (is the baud rate right?)", config_.timeout));
      break;
  }
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
  took_back();
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
  state_ = SenderState::Cancelled;
}

void Sender::fail(std::string message) {
  if (state_ == SenderState::Failed) return;
  state_ = SenderState::Failed;
  // The print ran until the last answer (the summary's time and rate).
  if (stats_.print_start >= 0 && stats_.print_end < stats_.print_start) stats_.print_end = last_any_rx_;
  failure_ = std::move(message);
}

std::string Sender::describe(const Position& p) const {
  if (p.number <= 0) return "none (no line was acknowledged)";
  if (p.source_line == 0) return fmt::format("N{}", p.number);
  if (p.layer <= 0) return fmt::format("line {} of the input (start code, before layer 1)", p.source_line);
  return fmt::format("line {} of the input (layer {})", p.source_line, p.layer);
}

}  // namespace gcode::serial
