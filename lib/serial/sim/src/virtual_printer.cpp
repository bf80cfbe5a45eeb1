#include "gcode/serial/sim/virtual_printer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "gcode/core/line.hpp"
#include "gcode/serial/protocol/protocol.hpp"

namespace gcode::serial {

namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();
constexpr double kKeepalive = 2.0;   // Marlin DEFAULT_KEEPALIVE_INTERVAL
constexpr double kHomingTime = 3.0;
constexpr double kStallTime = 3.0;
constexpr double kAmbient = 20.0;

}  // namespace

VirtualPrinter::VirtualPrinter(const VirtualPrinterConfig& config, std::FILE* log)
    : config_(config), log_(log), wire_(config.baud), schedule_(config.scheduled), rng_(config.seed) {
  if (const ReplyDialect* d = find_dialect(config.firmware)) dialect_ = d;
  next_idle_wait_ = config.idle_wait;
  if (std::string hello = dialect_->greeting(); !hello.empty()) send(hello);
}

bool VirtualPrinter::chance(double p) {
  if (p <= 0) return false;
  return std::uniform_real_distribution<double>(0, 1)(rng_) < p;
}

void VirtualPrinter::send(std::string_view text) {
  if (silent_ || halted_ || outage_.down()) return;
  stats_.tx_bytes += text.size() + 1;
  wire_.transmit(text, now_);
  last_sent_.assign(text);
}

bool VirtualPrinter::heated() const {
  // Within a degree, as Marlin's TEMP_WINDOW; the small slack absorbs rounding
  // of the heating steps, which would otherwise leave the wait a hair short.
  if (heating_bed_) return bed_ >= bed_target_ - 1 - 1e-6;
  return hotend_ >= hotend_target_ - 1 - 1e-6;
}

double VirtualPrinter::heat_done_time() const {
  if (heated()) return temp_time_;
  if (heating_bed_) return temp_time_ + (bed_target_ - 1 - bed_) / (config_.heat_rate / 3);
  return temp_time_ + (hotend_target_ - 1 - hotend_) / config_.heat_rate;
}

double VirtualPrinter::next_event() const {
  double t = std::min(wire_.next_arrival(), wire_.next_line_sent());
  if (disconnected_ || halted_ || silent_) return t;  // the firmware does nothing more
  if (!planner_.empty()) t = std::min(t, head_end_);
  switch (wait_) {
    case Wait::Dwell:
    case Wait::Homing:
    case Wait::Stall:
    case Wait::User: t = std::min(t, wait_until_); break;
    case Wait::Heating: t = std::min(t, heat_done_time()); break;
    default: break;
  }
  if (wait_ != Wait::None && wait_ != Wait::Heating) t = std::min(t, next_busy_);
  t = std::min({t, next_report_, idle_wait_at(), held_deadline()});
  return std::min({t, outage_.up_at(), schedule_.next_time()});
}

void VirtualPrinter::advance(double now) {
  for (;;) {
    double t_wire = wire_.next_arrival();
    double t_fw = kNever;
    if (!halted_ && !silent_ && !disconnected_) {
      if (!planner_.empty()) t_fw = head_end_;
      if (wait_ == Wait::Dwell || wait_ == Wait::Homing || wait_ == Wait::Stall || wait_ == Wait::User)
        t_fw = std::min(t_fw, wait_until_);
      if (wait_ == Wait::Heating) t_fw = std::min(t_fw, heat_done_time());
      if (wait_ != Wait::None && wait_ != Wait::Heating) t_fw = std::min(t_fw, next_busy_);
      t_fw = std::min({t_fw, next_report_, idle_wait_at(), outage_.up_at(), schedule_.next_time(), held_deadline()});
    }
    double t = std::min(t_wire, t_fw);
    if (t > now || t == kNever) break;
    if (t_wire <= t_fw) {
      arrive(wire_.arrive(), t_wire);
      continue;
    }
    now_ = std::max(now_, t);
    update_temperatures(t);
    while (!planner_.empty() && head_end_ <= t) planner_step(head_end_);
    if (wait_ != Wait::None && wait_ != Wait::Heating && next_busy_ <= t) {
      // (Klipper and RepRapFirmware keep quiet; nobody says busy while the user is asked.)
      if (dialect_->behaviour().busy_keepalive && wait_ != Wait::User) send(dialect_->busy());
      next_busy_ = t + kKeepalive;
    }
    if (next_report_ <= t) {
      bool heating = wait_ == Wait::Heating;
      send(dialect_->temperatures(temperatures(), heating));
      next_report_ = heating ? t + 1 : (autoreport_ > 0 ? t + autoreport_ : kNever);
    }
    if (idle_wait_at() <= t) {
      send(dialect_->idle());
      next_idle_wait_ = t + config_.idle_wait;
    }
    if (outage_.up_at() <= t) link_up(t);
    if (held_deadline() <= t) {
      // The write timed out: the rest of it is gone.
      stats_.overrun_bytes += held_.size();
      stats_.timed_out_bytes += held_.size();
      held_.clear();
    }
    for (ScheduledFault f; schedule_.take_due(t, f);) fire(f, t);
    run(t);
  }
  update_temperatures(std::max(now, temp_time_));
}

void VirtualPrinter::arrive(char c, double t) {
  ++stats_.rx_bytes;
  if (halted_ || silent_ || disconnected_) return;
  now_ = std::max(now_, t);
  // EMERGENCY_PARSER: M112 acts as it arrives, whatever the queue holds.
  if (c != '\n' && c != '\r') {
    if (emergency_.size() < 32) emergency_ += c;
  } else if (!emergency_.empty()) {
    std::string_view cmd = command_for_sending(emergency_);
    bool m112 = cmd.size() >= 4 && (cmd[0] == 'M' || cmd[0] == 'm') && cmd.substr(1, 3) == "112" &&
                (cmd.size() == 4 || cmd[4] < '0' || cmd[4] > '9');
    emergency_.clear();
    if (m112) {
      halt("Shutdown due to M112 command");
      if (halted_) return;  // (Klipper reads on, shut down)
    }
  }
  // Marlin keeps one slot of its ring buffer free.
  if (!dialect_->behaviour().reads_everything &&
      (!held_.empty() || rx_.size() - rx_head_ >= static_cast<std::size_t>(config_.rx_buffer - 1))) {
    if (config_.write_timeout > 0) {
      // The writer waits for room (OctoPrint's virtual printer).
      if (held_.empty()) {
        held_since_ = t;
        ++stats_.held_writes;
      }
      held_ += c;
      return;
    }
    ++stats_.overrun_bytes;
    return;
  }
  rx_ += c;
  // Between commands Marlin reads every byte as it comes (while its queue has
  // room), so a line longer than the RX buffer does not overrun an idle printer.
  if (wait_ == Wait::None) {
    run(t);
  } else if (dialect_->behaviour().reads_everything) {
    parse_rx();
  }
}

void VirtualPrinter::update_temperatures(double t) {
  double dt = t - temp_time_;
  if (dt <= 0) return;
  temp_time_ = t;
  auto step = [dt](double& temp, double target, double rate) {
    double goal = std::max(target, kAmbient);
    if (temp < goal) temp = std::min(goal, temp + rate * dt);
    else temp = std::max(goal, temp - rate / 2 * dt);
  };
  step(hotend_, hotend_target_, config_.heat_rate);
  step(bed_, bed_target_, config_.heat_rate / 3);
}

Temperatures VirtualPrinter::temperatures() const { return {hotend_, hotend_target_, bed_, bed_target_}; }

void VirtualPrinter::run(double t) {
  now_ = std::max(now_, t);
  while (!halted_ && !silent_ && !disconnected_) {
    if (wait_ != Wait::None) {
      if (still_waiting(t)) return;
      if (wait_ == Wait::Stall) {
        wait_ = Wait::None;
        start(t);
        continue;
      }
      finish(t);
      continue;
    }
    parse_rx();
    if (queue_.empty()) return;
    start(t);
  }
}

// A waiting write goes on as the buffer has room.
void VirtualPrinter::admit_held() {
  if (held_.empty()) return;
  std::size_t room = static_cast<std::size_t>(config_.rx_buffer - 1) - (rx_.size() - rx_head_);
  std::size_t n = std::min(room, held_.size());
  rx_.append(held_, 0, n);
  held_.erase(0, n);
  held_since_ = now_;
}

double VirtualPrinter::held_deadline() const {
  return held_.empty() ? kNever : held_since_ + config_.write_timeout;
}

void VirtualPrinter::parse_rx() {
  // Marlin's get_serial_commands(): read while the queue has room.
  admit_held();
  const bool everything = dialect_->behaviour().reads_everything;
  while ((everything || queue_.size() < static_cast<std::size_t>(config_.queue)) && rx_head_ < rx_.size() &&
         !halted_) {
    char c = rx_[rx_head_++];
    if (c == '\n' || c == '\r') {
      if (!partial_.empty()) {
        std::string line;
        line.swap(partial_);
        process_line(line);
        partial_.swap(line);
        partial_.clear();
      }
    } else if (partial_.size() + 1 < static_cast<std::size_t>(config_.max_line)) {
      // Marlin keeps MAX_CMD_SIZE - 1 bytes and skips the rest of the line,
      // its checksum included.
      partial_ += c;
    }
  }
  if (rx_head_ == rx_.size()) {
    rx_.clear();
    rx_head_ = 0;
  }
  admit_held();
}

void VirtualPrinter::reject(LineFault fault) {
  // Marlin drains its receive buffer after a bad line: whatever followed is
  // gone and must be resent too.
  stats_.drained_bytes += rx_.size() - rx_head_;
  rx_.clear();
  rx_head_ = 0;
  std::vector<std::string> answers = dialect_->rejected(fault, last_n_);
  // (Firmwares that send no ok after their resend request.)
  if (!config_.resend_ok && !answers.empty() && answers.back() == "ok") answers.pop_back();
  for (const std::string& answer : answers) send(answer);
}

bool VirtualPrinter::process_line(std::string& line) {
  if (!dialect_->behaviour().checks_line_numbers) {
    queue_unchecked(line);
    return true;
  }
  if (chance(config_.corrupt) && !line.empty()) {
    std::size_t i = std::uniform_int_distribution<std::size_t>(0, line.size() - 1)(rng_);
    line[i] = static_cast<char>(line[i] ^ (1 << std::uniform_int_distribution<int>(0, 5)(rng_)));
    if (line[i] == '\n' || line[i] == '\r' || line[i] == '\0') line[i] = '#';
    ++stats_.corrupted;
  }
  long long number = -1;
  std::string_view text = line;
  if (!line.empty() && line[0] == 'N') {
    bool m110 = line.find("M110") != std::string::npos;
    std::size_t npos = 0;
    if (m110) {
      std::size_t n2 = line.find('N', 4);
      if (n2 != std::string::npos) npos = n2;
    }
    long long n = std::strtoll(line.c_str() + npos + 1, nullptr, 10);
    if (n != last_n_ + 1 && !m110) {
      ++stats_.line_number_errors;
      reject(LineFault::LineNumber);
      return false;
    }
    std::size_t apos = line.rfind('*');
    if (apos == std::string::npos) {
      ++stats_.checksum_errors;
      reject(LineFault::NoChecksum);
      return false;
    }
    long long sum = std::strtoll(line.c_str() + apos + 1, nullptr, 10);
    if (sum != checksum(std::string_view(line).substr(0, apos))) {
      ++stats_.checksum_errors;
      reject(LineFault::Checksum);
      return false;
    }
    if (chance(config_.resend)) {
      ++stats_.spurious_resends;
      reject(LineFault::Checksum);
      return false;
    }
    if (scripted_error(n)) return false;
    last_n_ = n;
    number = n;
    ++stats_.accepted_lines;
    text = command_for_sending(text);
  } else if (line.find('*') != std::string::npos) {
    ++stats_.checksum_errors;
    reject(LineFault::NoLineNumber);
    return false;
  }
  push_command(text, number);
  return true;
}

// OctoPrint's virtual printer refuses lines 100, 105, 110 and 115 once each
// (its "simulated errors"): a resend, one whose ok is lost, a line taken
// for one without a number, a checksum mismatch.
bool VirtualPrinter::scripted_error(long long n) {
  static constexpr long long kLines[] = {100, 105, 110, 115};
  if (!config_.scripted_errors || scripted_fired_ >= 4 || n != kLines[scripted_fired_]) return false;
  const int which = scripted_fired_++;
  ++stats_.scripted_errors;
  const bool resend_ok = config_.resend_ok;
  if (which == 1) config_.resend_ok = false;
  reject(which == 2 ? LineFault::NoLineNumber : LineFault::Checksum);
  config_.resend_ok = resend_ok;
  return true;
}

// Klipper reads "N12" and "*34" and ignores them: the number is kept for
// the log only.
void VirtualPrinter::queue_unchecked(std::string_view line) {
  long long number = -1;
  if (!line.empty() && line[0] == 'N') number = std::strtoll(std::string(line.substr(1, 20)).c_str(), nullptr, 10);
  if (number >= 0) ++stats_.accepted_lines;
  push_command(command_for_sending(line), number);
}

void VirtualPrinter::push_command(std::string_view text, long long number) {
  Command cmd;
  if (!spare_.empty()) {
    cmd = std::move(spare_.back());
    spare_.pop_back();
  }
  cmd.text.assign(text);
  cmd.number = number;
  queue_.push_back(std::move(cmd));
  next_idle_wait_ = now_ + config_.idle_wait;
}

// Marlin's NO_TIMEOUTS: "wait" while nothing is queued or arriving, from the
// last command on.
double VirtualPrinter::idle_wait_at() const {
  if (config_.idle_wait <= 0 || !queue_.empty() || rx_head_ < rx_.size() || !partial_.empty()) return kNever;
  return next_idle_wait_;
}

void VirtualPrinter::add_block(double duration, double t) {
  if (planner_.empty()) {
    head_end_ = t + duration;
    if (empty_since_ >= 0 && !waited_while_empty_ && stats_.first_move >= 0) stats_.starved += t - empty_since_;
    if (stats_.first_move < 0) stats_.first_move = t;
    stats_.last_move_end = t + duration;
  } else {
    stats_.last_move_end += duration;
  }
  empty_since_ = -1;
  planner_.push_back(duration);
  lengths_.push_back(pending_length_);
  block_numbers_.push_back(queue_.empty() ? -1 : queue_.front().number);
  queued_length_ += pending_length_;
  ++stats_.moves;
}

void VirtualPrinter::planner_step(double t) {
  planner_.pop_front();
  done_length_ += lengths_.front();
  lengths_.pop_front();
  block_numbers_.pop_front();
  if (!planner_.empty()) {
    head_end_ = t + planner_.front();
  } else {
    empty_since_ = t;
    waited_while_empty_ = false;
  }
}

void VirtualPrinter::send_ok(long long number) {
  if (chance(config_.drop_ok)) {
    ++stats_.dropped_oks;
    return;
  }
  // The queue still holds the command being acknowledged, as in Marlin.
  int planner_free = planner_capacity() - static_cast<int>(planner_.size());
  int queue_free = config_.queue - static_cast<int>(queue_.size());
  send(dialect_->ok(number, config_.advanced_ok, planner_free, queue_free));
}

// The head command starts; it either completes now (finish) or sets a wait.
void VirtualPrinter::start(double t) {
  Command& c = queue_.front();
  if (wait_ != Wait::Stall && chance(config_.busy)) {
    ++stats_.busy_stalls;
    wait_ = Wait::Stall;
    wait_until_ = t + kStallTime;
    next_busy_ = t + kKeepalive;
    return;
  }
  wait_ = Wait::None;
  if (c.number == watch_.number && !watch_.seen) {
    watch_.seen = true;
    watch_.motion_end = planner_.empty() ? std::max(0.0, stats_.last_move_end) : stats_.last_move_end;
    watch_.queued_length = queued_length_;
  }
  Line line = Line::parse(c.text);
  if (refused(line)) return;
  Move m = state_.apply(line);
  if (execute(line, m, t)) finish(t);
}

// One handler per command; true: done now (its ok goes out), false: it waits.
bool VirtualPrinter::execute(const Line& line, const Move& m, double t) {
  if (!dialect_->knows(line)) return process_unknown(line);
  if (line.kind == CommandKind::Extended) return process_extended(line);
  if (m.kind == MoveKind::Linear || m.kind == MoveKind::Arc) return process_move(m, t);
  if (line.kind != CommandKind::Standard) return true;
  if (line.letter == 'G') {
    switch (line.number) {
      case 4: return process_G4(line, t);
      case 28: case 29: return process_G28(t);
      default: return true;
    }
  }
  if (line.letter != 'M') return true;
  switch (line.number) {
    case 104: case 140: return process_M104(line);
    case 105: return process_M105();
    case 109: case 190: return process_M109(line, t);
    case 110: return process_M110(line);
    case 112: return process_M112();
    case 114: return process_M114();
    case 115: return line.find('U') != nullptr ? process_M115_version(line, t) : process_M115();
    case 155: return process_M155(line, t);
    case 400: return process_M400(t);
    case 600: return process_M600(t);
    case 601: return process_M601(t);
    default: return true;
  }
}

// A command the firmware does not know (Marlin: extended and host commands).
bool VirtualPrinter::process_unknown(const Line& line) {
  send(dialect_->unknown_command(line.code()));
  return true;
}

// G0-G3: a block of the planner once one is free (its ok waits until then).
// One that moves nothing (a bare G1) waits on Marlin too, then takes none:
// Planner::_buffer_steps waits in get_next_free_block before
// _populate_block drops a block of no steps.
bool VirtualPrinter::process_move(const Move& m, double t) {
  double length = m.length > 0 ? m.length : std::abs(m.filament);
  pending_block_ = length > 0;
  if (!pending_block_) {
    if (!dialect_->behaviour().empty_move_waits || !planner_full(t)) return true;
    wait_ = Wait::PlannerSlot;
    next_busy_ = t + kKeepalive;
    return false;
  }
  double feed = m.feedrate > 0 ? m.feedrate : 1500;
  pending_duration_ = config_.instant_moves ? 0 : length / (feed / 60) / config_.speed_factor;
  pending_length_ = m.length;
  if (m.extruding && state_.position[kZ] > top_z_ + 1e-6) {
    top_z_ = state_.position[kZ];
    started_layer_ = ++layer_;
  }
  if (planner_full(t)) {
    wait_ = Wait::PlannerSlot;
    next_busy_ = t + kKeepalive;
    return false;
  }
  add_block(pending_duration_, t);
  return true;
}

// Klipper takes moves while less than buffer_seconds of motion are queued;
// Marlin while its planner has a free block.
bool VirtualPrinter::planner_full(double t) const {
  double ahead = dialect_->behaviour().buffer_seconds;
  if (ahead > 0) return !planner_.empty() && stats_.last_move_end - t > ahead + 1e-9;
  return planner_.size() >= static_cast<std::size_t>(planner_capacity());
}

// Marlin's planner is a ring buffer that keeps one block empty: a
// BLOCK_BUFFER_SIZE of 16 holds 15 moves and answers "ok P15" when idle
// (planner.h moves_free(); seen on Marlin 2.0.7.2's Linux HAL).
int VirtualPrinter::planner_capacity() const { return std::max(1, config_.planner - 1); }

// Waits for the planner to empty, then `after` for `duration`.
bool VirtualPrinter::wait_for_planner(double t, After after, double duration) {
  wait_ = Wait::PlannerEmpty;
  next_busy_ = t + kKeepalive;
  after_ = after;
  after_duration_ = duration;
  return false;
}

// G4 P<ms> S<s>: dwell, after the moves before it.
bool VirtualPrinter::process_G4(const Line& line, double t) {
  return wait_for_planner(t, After::Dwell, line.value_or('P', 0) / 1000 + line.value_or('S', 0));
}

// G28, G29: homing or probing, after the moves before it.
bool VirtualPrinter::process_G28(double t) {
  homed_ = !config_.home_fails;
  homing_fails_ = config_.home_fails;
  return wait_for_planner(t, After::Home, config_.instant_moves ? 0 : kHomingTime);
}

// M400: waits for the moves to end.
bool VirtualPrinter::process_M400(double t) { return wait_for_planner(t, After::Nothing, 0); }

// M104/M140 S|R: a hot end or bed target, no wait.
bool VirtualPrinter::process_M104(const Line& line) {
  set_target(line);
  return true;
}

void VirtualPrinter::set_target(const Line& line) {
  if (line.is_m(104) || line.is_m(109)) hotend_target_ = line.value_or('S', line.value_or('R', hotend_target_));
  if (line.is_m(140) || line.is_m(190)) bed_target_ = line.value_or('S', line.value_or('R', bed_target_));
}

// M109/M190: the target, then a wait until it is reached, reporting every second.
bool VirtualPrinter::process_M109(const Line& line, double t) {
  set_target(line);
  heating_bed_ = line.is_m(190);
  wait_ = Wait::Heating;
  waited_while_empty_ = true;
  next_report_ = std::min(next_report_, t + 1);
  return false;
}

// M105: the temperatures on the ok line; a Klipper shut down answers
// "ok T:0" (gcode.py's cmd_default: its heaters are gone with the MCU).
bool VirtualPrinter::process_M105() {
  send(flavour_.shut_down() ? std::string("ok T:0") : dialect_->temperature_ok(temperatures()));
  ok_sent_ = true;
  return true;
}

// M110 N<n>: the next line number is n + 1 (Klipper: nothing).
bool VirtualPrinter::process_M110(const Line& line) {
  if (line.find('N') != nullptr && dialect_->behaviour().checks_line_numbers) last_n_ = static_cast<long long>(line.value_or('N', 0));
  return true;
}

// M112 (without the emergency parser's head start): halt at once, no ok
// (Klipper, which answers while shut down: with its ok).
bool VirtualPrinter::process_M112() {
  halt("Shutdown due to M112 command");
  return flavour_.shut_down();
}

// M114: the position and the step counts (80 steps/mm XY, 400 Z).
bool VirtualPrinter::process_M114() {
  send(dialect_->position(state_.position[kX], state_.position[kY], state_.position[kZ], state_.position[kE],
                          std::lround(state_.machine(kX) * 80), std::lround(state_.machine(kY) * 80),
                          std::lround(state_.machine(kZ) * 400)));
  return true;
}

// M115: the firmware and its capabilities (Klipper: on the ok line).
bool VirtualPrinter::process_M115() {
  for (const std::string& l : dialect_->firmware_report(config_)) send(l);
  ok_sent_ = dialect_->behaviour().report_on_ok;
  return true;
}

// M155 S<s>: temperature autoreport every s seconds (0: off).
bool VirtualPrinter::process_M155(const Line& line, double t) {
  autoreport_ = line.value_or('S', 0);
  next_report_ = autoreport_ > 0 ? t + autoreport_ : (wait_ == Wait::Heating ? next_report_ : kNever);
  return true;
}

bool VirtualPrinter::still_waiting(double t) {
  switch (wait_) {
    case Wait::None: return false;
    case Wait::PlannerSlot:
      if (planner_full(t)) return true;
      if (pending_block_) add_block(pending_duration_, t);
      return false;
    case Wait::PlannerEmpty:
      if (!planner_.empty()) return true;
      if (after_ == After::Nothing) return false;
      wait_ = after_ == After::Home ? Wait::Homing : after_ == After::Dwell ? Wait::Dwell : Wait::User;
      if (after_ == After::OwnPause) {
        flavour_.own_pause();
        send(dialect_->paused());
      }
      wait_until_ = t + after_duration_;
      waited_while_empty_ = true;
      after_ = After::Nothing;
      return t < wait_until_;
    case Wait::Dwell:
    case Wait::Homing:
    case Wait::Stall: return t < wait_until_;
    case Wait::User: return t < wait_until_ || end_user_wait();
    case Wait::Heating: {
      update_temperatures(t);
      bool done = heated();
      if (done && autoreport_ <= 0) next_report_ = kNever;
      return !done;
    }
  }
  return false;
}

void VirtualPrinter::finish(double t) {
  Command& c = queue_.front();
  long long number = c.number;
  ++stats_.executed;
  if (log_ != nullptr) {
    std::fprintf(log_, "%.6f\t%lld\t%.3f\t%.3f\t%.3f\t%.5f\t%s\n", t, c.number, state_.position[kX],
                 state_.position[kY], state_.position[kZ], state_.position[kE], c.text.c_str());
  }
  if (homing_fails_) fail_homing();
  if (!ok_sent_) send_ok(c.number);
  ok_sent_ = false;
  if (chance(config_.garbage)) {
    ++stats_.garbage_lines;
    static constexpr char kJunk[] = "#$%&()+-<=>?[]^_{|}~0123456789 \x7f\x1b";
    std::string junk;
    int n = std::uniform_int_distribution<int>(1, 40)(rng_);
    for (int i = 0; i < n; ++i) junk += kJunk[std::uniform_int_distribution<std::size_t>(0, sizeof kJunk - 2)(rng_)];
    send(junk);
  }
  long long done = static_cast<long long>(stats_.executed);
  if (done == config_.halt_after) {
    send(dialect_->thermal_runaway());
    halt("Heater extruder not heating at expected rate");
  }
  if (done == config_.silent_after) silent_ = true;
  if (done == config_.unhome_after) homed_ = false;
  if (done == config_.disconnect_after) disconnected_ = true;
  spare_.push_back(std::move(c));
  queue_.pop_front();
  if (spare_.size() > 8) spare_.pop_front();
  next_idle_wait_ = t + config_.idle_wait;
  wait_ = Wait::None;
  ScheduledFault fault;
  bool due = schedule_.take_after_command(number, started_layer_, fault);
  started_layer_ = 0;
  if (due) fire(fault, t);
  if (flavour_.take_restart()) reset(t);
}

double VirtualPrinter::travelled(double t) const {
  double path = done_length_;
  double start = planner_.empty() ? t : head_end_ - planner_.front();
  for (std::size_t i = 0; i < planner_.size(); ++i) {
    double end = start + planner_[i];
    if (t >= end) {
      path += lengths_[i];
    } else {
      if (t > start && planner_[i] > 0) path += lengths_[i] * (t - start) / planner_[i];
      break;
    }
    start = end;
  }
  return path;
}

double VirtualPrinter::starvation() const {
  double span = stats_.last_move_end - stats_.first_move;
  return span > 0 ? stats_.starved / span : 0;
}

}  // namespace gcode::serial
