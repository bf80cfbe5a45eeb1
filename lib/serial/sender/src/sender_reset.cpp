// The sender's side of a printer reset: what the print has done so far,
// kept for every command it numbers (track), and the way back that
// ResetRecovery (reset_recovery.hpp) decides, applied: the commands after
// the one that surely ran renumbered on from the last number that went
// out, the handshake again, the link as a restarted printer has it.
#include <algorithm>
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

void Sender::printer_reset(std::string_view how, double now) {
  if (finished()) return;
  homing_.forget();  // the way back homes X and Y again
  const long long back = recovery_.back_to(*this, last_acked_.number, clock_.planner_blocks(), next_number_);
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
  const ResetRecovery::Redone redone = ResetRecovery::may_print_twice(*this, last_acked_.number, back);
  std::vector<std::string> sequence;
  if (back > 0) {
    const PrintStep& t = held(back);
    try {
      sequence = reset_resume_lines(ResetRecovery::way_back(t, redone), Precision());
    } catch (const std::invalid_argument& e) {
      fail(fmt::format("the printer reset ({}) and cannot be brought back: {}; last acknowledged: {}", how, e.what(),
                       describe(last_acked_)));
      return;
    }
    if (redone.z_high > redone.z_low + 1e-9)
      log(LogLevel::Warning, t.source_line,
          fmt::format("the nozzle stopped somewhere between Z {:.3f} and Z {:.3f}; taken to be at Z {:.3f}",
                      redone.z_low, redone.z_high, redone.z_high));
  }
  ++stats_.resets;
  stats_.redone_moves += static_cast<std::uint64_t>(redone.moves);
  stats_.redone_mm += redone.mm;
  const Position from{back, back > 0 ? held(back).source_line : 0, back > 0 ? held(back).layer : 0};
  log(LogLevel::Warning, from.source_line,
      back == 0 ? fmt::format("the printer reset ({}) before anything was printed; starting the print again", how)
                : fmt::format("the printer reset ({}) after {}; going back to {}: heating, Z declared, X and Y homed, "
                              "{} moves ({:.1f} mm) may print twice",
                              how, describe(last_acked_), describe(from), redone.moves, redone.mm));
  if (resubmit_after_reset(back, sequence)) restart_handshake(now);
}

// Everything after `back` in the print's order goes out again, after the
// sequence, numbered on from the highest number used.
bool Sender::resubmit_after_reset(long long back, const std::vector<std::string>& sequence) {
  std::vector<Again> again;
  for (long long n : ResetRecovery::given_again(*this, last_enqueued_, back, final_queued_)) {
    const Slot& s = slot(n);
    again.push_back({std::string(command_of_numbered(s.wire)), s.source_line, s.layer});
  }
  final_queued_ = false;
  const MachineState target = back > 0 ? held(back).after : MachineState{};
  const ResumeTrack track = back > 0 ? held(back).track : ResumeTrack{};
  const int layer = back > 0 ? held(back).layer : 0;
  // The numbers that never went out (commands the pacer or a block held)
  // are free again: the handshake names the last number that went out, whose
  // journal record was written before it did.
  next_number_ = next_send_ = highest_sent_ + 1;
  resent_above_highest_ = 0;  // every waiting line is numbered anew
  handshake_.number_on_from(highest_sent_);
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
  if (!sequence.empty()) journal_first_send(handshake_.number() + 1);
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
  relocator_.forget();
  timeouts_in_row_ = 0;
  last_rx_ = now;
  begin_handshake(now);  // M110: the numbering goes on from the print
}

void Sender::continue_after_reset(long long last_number, long long restore, int layer,
                                  const std::vector<std::string>& sequence, const MachineState& target,
                                  const ResumeTrack& track, std::uint64_t source_line) {
  next_number_ = next_send_ = last_number + 1;
  highest_sent_ = journaled_ = last_number;
  resent_above_highest_ = 0;
  handshake_.number_on_from(last_number);
  last_acked_.number = last_number;
  first_held_ = last_number + 1;
  last_enqueued_ = restore;  // the sequence follows the command it goes back to
  config_.handshake = true;
  track_ = track;
  // The command the sequence goes back to: another reset before the print
  // is past 16 moves again goes back to it once more.
  recovery_.hold_base(restore, target, track, source_line, layer);
  restoring_ = restore;
  for (const std::string& line : sequence) enqueue(line, 0, layer);
  restoring_ = 0;
  machine_ = target;
}

}  // namespace gcode::serial
