// The printer reset mid-print (its greeting came, or after a reconnect its
// line numbers are back at 0): whatever it had queued or planned is lost,
// but the part stands on the bed. Marlin answers a move once it has a
// planner block, so of the moves it acknowledged only the newest
// `planner_blocks` may not have run (fewer when an M400, G28 or G4 was
// acknowledged after them: those answer once every move before them ran).
// The print goes back to the command before the oldest of them: the
// handshake again (M110 N numbers on from the highest number ever used, so
// a number names one command in the journal), the resume sequence
// (reset_sequence.hpp: heat, declare Z, lift, home X and Y, travel, descend,
// prime, modes), then every command after that one in the print's order.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/core/line.hpp"
#include "gcode/serial/protocol/line_check.hpp"
#include "gcode/serial/sender/sender.hpp"

namespace gcode::serial {

namespace {

struct Again {
  std::string command;
  std::uint64_t source_line = 0;
  int layer = 0;
};

}  // namespace

std::string Sender::handshake_line() const { return fmt::format("M110 N{}", handshake_number_); }

void Sender::track(Slot& s, const Line& line, const Move& move) {
  s.drains = line.is_m(400) || line.is_g(28) || line.is_g(29) || line.is_g(4);
  s.prev = last_enqueued_;
  last_enqueued_ = next_number_;
  s.restore = restoring_;
  track_.step(move.filament, move.moves_head(), machine_.position[kZ], s.source_line == 0);
  if (line.is_g(10) && machine_.firmware_retracted && s.source_line != 0) {
    // A firmware retraction moves no E of the file's: the firmware pulls
    // back what it is set to (M207, the profile, else its defaults) and its
    // G11 pushes that and the extra. A resume after a reset primes as much,
    // as after a retraction (a reset printer starts unretracted).
    const PlannerLimits& fw = estimator_.limits();
    track_.retraction = std::max(track_.retraction, fw.fw_retract_length + fw.fw_unretract_extra);
  }
  s.after = machine_;
  s.track = track_;
}

void Sender::took_back() {
  last_enqueued_ = next_number_ - 1;
  if (in_history(last_enqueued_)) track_ = slot(last_enqueued_).track;
}

// The newest command that surely ran: 0 none (the print starts again), -1
// when the way back is no longer held.
long long Sender::surely_ran() const {
  const int blocks = clock_.planner_blocks();
  int moves = 0;
  long long n = last_acked_.number;
  while (n > 0) {
    if (n == base_number_) return n;
    // Acknowledged before this session's first line (a resume's handshake):
    // nothing past the base is known to have run.
    if (!in_history(n)) return n < first_held_ && base_number_ > 0 ? base_number_ : -1;
    const Slot& s = slot(n);
    // A line of an earlier resume: that resume starts again.
    if (s.restore != 0) return in_history(s.restore) || s.restore == base_number_ ? s.restore : -1;
    if (s.drains || moves == blocks) return n;
    if (s.move) ++moves;
    n = s.prev;
  }
  return 0;
}

void Sender::printer_reset(std::string_view how, double now) {
  if (finished()) return;
  long long back = surely_ran();
  // Nothing extruded yet: no part on the bed, the start code homes Z too
  // (only where this sender sent the print from its first line).
  if (back > 0 && held(back).track.top_z <= 0) back = 0;
  if (back == 0 && (first_held_ != 1 || (next_number_ > 1 && !in_history(1)))) back = -1;
  if (back < 0) {
    fail(fmt::format("the printer reset ({}) and the commands it may have lost are no longer held; last "
                     "acknowledged: {}",
                     how, describe(last_acked_)));
    return;
  }
  if (back > 0 && !config_.home_xy_alone) {
    fail(fmt::format("the printer reset ({}); last acknowledged: {}; {}", how, describe(last_acked_),
                     xy_homing_refusal(held(back).after.position[kZ], "")));
    return;
  }
  // What may print twice: the acknowledged moves after `back`.
  int moves = 0;
  double mm = 0;
  double z_low = 1e300, z_high = -1e300;
  for (long long n = last_acked_.number; n > back; n = slot(n).prev) {
    const Slot& s = slot(n);
    if (s.restore != 0) continue;
    const MachineState& m = s.after;
    const double z = m.lifted ? m.lift_base_z : m.position[kZ];
    z_low = std::min(z_low, z);
    z_high = std::max(z_high, z);
    if (!s.move) continue;
    ++moves;
    const std::array<double, 3>& a = held(s.prev).at;
    mm += std::hypot(s.at[0] - a[0], s.at[1] - a[1], s.at[2] - a[2]);
  }
  std::vector<std::string> sequence;
  if (back > 0) {
    const Slot& t = held(back);
    ResetResume way{t.after, t.track.top_z, std::max(z_high, t.after.position[kZ]), t.track.retracted,
                    t.track.retraction};
    // Inside a block of gc-send's own (a pause's): the filament is where the
    // block left it, its way back primes.
    if (t.source_line == 0) way.retracted = way.prime = 0;
    // Where the nozzle stopped is known to be one of those heights only:
    // the highest is taken (too high prints into the air for a layer; too
    // low would push the nozzle into the part).
    if (z_high <= t.after.position[kZ]) way.nozzle_z = std::numeric_limits<double>::quiet_NaN();
    try {
      sequence = reset_resume_lines(way, Precision());
    } catch (const std::invalid_argument& e) {
      fail(fmt::format("the printer reset ({}) and cannot be brought back: {}; last acknowledged: {}", how, e.what(),
                       describe(last_acked_)));
      return;
    }
    if (z_high > z_low + 1e-9)
      log(LogLevel::Warning, t.source_line,
          fmt::format("the nozzle stopped somewhere between Z {:.3f} and Z {:.3f}; taken to be at Z {:.3f}", z_low,
                      z_high, z_high));
  }
  ++stats_.resets;
  stats_.redone_moves += static_cast<std::uint64_t>(moves);
  stats_.redone_mm += mm;
  const Position from{back, back > 0 ? held(back).source_line : 0, back > 0 ? held(back).layer : 0};
  log(LogLevel::Warning, from.source_line,
      back == 0 ? fmt::format("the printer reset ({}) before anything was printed; starting the print again", how)
                : fmt::format("the printer reset ({}) after {}; going back to {}: heating, Z declared, X and Y homed, "
                              "{} moves ({:.1f} mm) may print twice",
                              how, describe(last_acked_), describe(from), moves, mm));
  if (resubmit_after_reset(back, sequence)) restart_handshake(now);
}

// Everything after `back` in the print's order goes out again, after the
// sequence, numbered on from the highest number used.
bool Sender::resubmit_after_reset(long long back, const std::vector<std::string>& sequence) {
  std::vector<Again> again;
  for (long long n = last_enqueued_; n != back && n > 0; n = slot(n).prev) {
    const Slot& s = slot(n);
    if (s.restore != 0) continue;  // an earlier resume's lines: made anew
    if (final_queued_ && n == last_enqueued_ && s.source_line == 0) continue;  // the final M400: added again
    again.push_back({std::string(command_of_numbered(s.wire)), s.source_line, s.layer});
  }
  std::reverse(again.begin(), again.end());
  final_queued_ = false;
  const MachineState target = back > 0 ? held(back).after : MachineState{};
  const ResumeTrack track = back > 0 ? held(back).track : ResumeTrack{};
  const int layer = back > 0 ? held(back).layer : 0;
  // The numbers that never went out (commands the pacer or a block held)
  // are free again: the handshake names the last number that went out, whose
  // journal record was written before it did.
  next_number_ = next_send_ = highest_sent_ + 1;
  handshake_number_ = highest_sent_;
  journaled_ = std::min(journaled_, highest_sent_);
  last_enqueued_ = back;
  machine_ = MachineState{};
  track_ = track;
  restoring_ = back;
  for (const std::string& line : sequence) enqueue(line, 0, layer);
  restoring_ = 0;
  machine_ = target;
  for (const Again& a : again) {
    // A higher number makes a line longer: it must still fit the buffer.
    LineCheck check = check_line(a.command, next_number_, config_.max_line);
    if (check.problem != LineProblem::None && check.problem != LineProblem::Shortened) {
      fail(fmt::format("the printer reset, and input line {} no longer fits under its new number: {}", a.source_line,
                       serial::describe(check, config_.max_line)));
      return false;
    }
    enqueue(check.problem == LineProblem::Shortened ? check.command : a.command, a.source_line, a.layer);
  }
  // The way back's first line is journaled before the handshake goes out: a
  // gc-send stopped between the two finds, on --resume, the printer at the
  // handshake's number and the way back right after it in the journal.
  if (!sequence.empty()) journal_first_send(handshake_number_ + 1);
  return true;
}

// The link as a restarted printer has it: nothing in flight, no numbers.
void Sender::restart_handshake(double now) {
  // A line the reset cut off (part of it written): a newline ends the
  // fragment, which a printer that kept its buffer refuses on its own (no
  // checksum) instead of reading it glued to the handshake.
  const bool cut = out_pos_ > 0 && out_[out_pos_ - 1] != '\n';
  out_total_ -= out_.size() - out_pos_;
  if (out_.size() > out_pos_) ++output_discards_;
  out_.clear();
  out_pos_ = 0;
  if (cut) {
    out_ += '\n';
    ++out_total_;
  }
  flight_.clear();
  resend_ = ResendState();
  probes_ = ProbeBackoff();
  pacer_ = Pacer();
  idle_hint_ = false;
  paused_ = false;
  relink_ = Relink::None;
  position_asked_ = false;
  timeouts_in_row_ = 0;
  last_rx_ = now;
  begin_handshake(now);  // M110: the numbering goes on from the print
}

void Sender::continue_after_reset(long long last_number, long long restore, int layer,
                                  const std::vector<std::string>& sequence, const MachineState& target,
                                  const ResumeTrack& track, std::uint64_t source_line) {
  next_number_ = next_send_ = last_number + 1;
  highest_sent_ = handshake_number_ = journaled_ = last_number;
  last_acked_.number = last_number;
  first_held_ = last_number + 1;
  last_enqueued_ = restore;  // the sequence follows the command it goes back to
  config_.handshake = true;
  track_ = track;
  // The command the sequence goes back to: another reset before the print
  // is past 16 moves again goes back to it once more.
  hold_base(restore, target, track, source_line, layer);
  restoring_ = restore;
  for (const std::string& line : sequence) enqueue(line, 0, layer);
  restoring_ = 0;
  machine_ = target;
}

}  // namespace gcode::serial
