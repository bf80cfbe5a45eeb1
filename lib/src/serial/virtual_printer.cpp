#include "gcode/serial/virtual_printer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "gcode/core/line.hpp"
#include "gcode/serial/protocol.hpp"

namespace gcode::serial {

namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();
constexpr double kKeepalive = 2.0;   // Marlin DEFAULT_KEEPALIVE_INTERVAL
constexpr double kHomingTime = 3.0;
constexpr double kStallTime = 3.0;
constexpr double kAmbient = 20.0;

double parse_value(std::string_view key, std::string_view value) {
  double v = 0;
  auto res = std::from_chars(value.data(), value.data() + value.size(), v);
  if (res.ec != std::errc() || res.ptr != value.data() + value.size() || !std::isfinite(v) || v < 0)
    throw std::invalid_argument(fmt::format("virtual printer option {}: '{}' is not a number >= 0", key, value));
  return v;
}

bool parse_flag(std::string_view key, std::string_view value) {
  if (value.empty() || value == "1" || value == "on" || value == "yes" || value == "true") return true;
  if (value == "0" || value == "off" || value == "no" || value == "false") return false;
  throw std::invalid_argument(fmt::format("virtual printer option {}: '{}' is not on/off", key, value));
}

double probability(std::string_view key, std::string_view value) {
  double p = parse_value(key, value);
  if (p > 1) throw std::invalid_argument(fmt::format("virtual printer option {}: {} is not a probability", key, value));
  return p;
}

}  // namespace

void parse_virtual_options(std::string_view text, VirtualPrinterConfig& c) {
  while (!text.empty()) {
    std::size_t comma = text.find(',');
    std::string_view item = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
    if (item.empty()) continue;
    std::size_t eq = item.find('=');
    std::string_view key = item.substr(0, eq);
    std::string_view value = eq == std::string_view::npos ? std::string_view() : item.substr(eq + 1);
    auto count = [&](double lo) {
      double v = parse_value(key, value);
      if (v < lo || v != std::floor(v))
        throw std::invalid_argument(fmt::format("virtual printer option {}: '{}' must be a whole number >= {}", key, value, lo));
      return v;
    };
    if (key == "baud") {
      c.baud = count(50);
    } else if (key == "queue") {
      c.queue = static_cast<int>(count(1));
    } else if (key == "rx") {
      c.rx_buffer = static_cast<int>(count(16));
    } else if (key == "max-line") {
      c.max_line = static_cast<int>(count(16));
    } else if (key == "planner") {
      c.planner = static_cast<int>(count(1));
    } else if (key == "time-scale") {
      c.time_scale = parse_value(key, value);
      if (c.time_scale <= 0) throw std::invalid_argument("virtual printer option time-scale must be > 0");
    } else if (key == "advanced-ok") {
      c.advanced_ok = parse_flag(key, value);
    } else if (key == "instant-moves") {
      c.instant_moves = parse_flag(key, value);
    } else if (key == "report-link") {
      c.report_link = parse_flag(key, value);
    } else if (key == "heat-rate") {
      c.heat_rate = std::max(0.01, parse_value(key, value));
    } else if (key == "corrupt") {
      c.corrupt = probability(key, value);
    } else if (key == "drop-ok") {
      c.drop_ok = probability(key, value);
    } else if (key == "resend") {
      c.resend = probability(key, value);
    } else if (key == "garbage") {
      c.garbage = probability(key, value);
    } else if (key == "busy") {
      c.busy = probability(key, value);
    } else if (key == "silent-after") {
      c.silent_after = static_cast<long long>(count(0));
    } else if (key == "halt-after") {
      c.halt_after = static_cast<long long>(count(0));
    } else if (key == "disconnect-after") {
      c.disconnect_after = static_cast<long long>(count(0));
    } else if (key == "log") {
      c.log_path = std::string(value);
    } else if (key == "seed") {
      c.seed = static_cast<std::uint32_t>(count(0));
    } else {
      throw std::invalid_argument(fmt::format("unknown virtual printer option '{}'", key));
    }
  }
}

VirtualPrinter::VirtualPrinter(const VirtualPrinterConfig& config, std::FILE* log)
    : config_(config), log_(log), byte_time_(10.0 / config.baud), rng_(config.seed) {
  send("start");
}

bool VirtualPrinter::chance(double p) {
  if (p <= 0) return false;
  return std::uniform_real_distribution<double>(0, 1)(rng_) < p;
}

void VirtualPrinter::receive(std::string_view bytes, double now) {
  if (bytes.empty()) return;
  if (wire_head_ == wire_.size()) {
    wire_.clear();
    wire_head_ = 0;
    wire_next_ = std::max(now, wire_next_) + byte_time_;
  }
  wire_.append(bytes);
}

void VirtualPrinter::send(std::string_view text) {
  if (silent_ || halted_) return;
  tx_.append(text);
  tx_ += '\n';
  stats_.tx_bytes += text.size() + 1;
  tx_free_at_ = std::max(tx_free_at_, now_) + static_cast<double>(text.size() + 1) * byte_time_;
}

std::string_view VirtualPrinter::transmitted(double now) const {
  std::size_t pending = tx_.size() - tx_head_;
  if (pending == 0) return {};
  double left = (tx_free_at_ - now) / byte_time_;  // bytes still on the way
  std::size_t not_done = left <= 0 ? 0 : static_cast<std::size_t>(std::ceil(left - 1e-6));
  std::size_t done = not_done >= pending ? 0 : pending - not_done;
  return std::string_view(tx_).substr(tx_head_, done);
}

void VirtualPrinter::take(std::size_t n) {
  tx_head_ += n;
  if (tx_head_ == tx_.size()) {
    tx_.clear();
    tx_head_ = 0;
  } else if (tx_head_ > (1u << 16)) {
    tx_.erase(0, tx_head_);
    tx_head_ = 0;
  }
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
  double t = kNever;
  if (wire_head_ < wire_.size()) t = wire_next_;
  std::size_t pending = tx_.size() - tx_head_;
  if (pending > 0) {
    // Wake when the next whole line has been sent, not for every byte.
    std::size_t nl = tx_.find('\n', tx_head_);
    std::size_t upto = nl == std::string::npos ? tx_.size() : nl + 1;
    t = std::min(t, tx_free_at_ - static_cast<double>(tx_.size() - upto) * byte_time_);
  }
  if (disconnected_ || halted_ || silent_) return t;  // the firmware does nothing more
  if (!planner_.empty()) t = std::min(t, head_end_);
  switch (wait_) {
    case Wait::Dwell:
    case Wait::Homing:
    case Wait::Stall: t = std::min(t, wait_until_); break;
    case Wait::Heating: t = std::min(t, heat_done_time()); break;
    default: break;
  }
  if (wait_ != Wait::None && wait_ != Wait::Heating) t = std::min(t, next_busy_);
  t = std::min(t, next_report_);
  return t;
}

void VirtualPrinter::advance(double now) {
  for (;;) {
    double t_wire = wire_head_ < wire_.size() ? wire_next_ : kNever;
    double t_fw = kNever;
    if (!halted_ && !silent_ && !disconnected_) {
      if (!planner_.empty()) t_fw = head_end_;
      if (wait_ == Wait::Dwell || wait_ == Wait::Homing || wait_ == Wait::Stall) t_fw = std::min(t_fw, wait_until_);
      if (wait_ == Wait::Heating) t_fw = std::min(t_fw, heat_done_time());
      if (wait_ != Wait::None && wait_ != Wait::Heating) t_fw = std::min(t_fw, next_busy_);
      t_fw = std::min(t_fw, next_report_);
    }
    double t = std::min(t_wire, t_fw);
    if (t > now || t == kNever) break;
    if (t_wire <= t_fw) {
      char c = wire_[wire_head_++];
      wire_next_ += byte_time_;
      if (wire_head_ == wire_.size()) {
        wire_next_ -= byte_time_;  // the time the last byte arrived
        wire_.clear();
        wire_head_ = 0;
      }
      arrive(c, t_wire);
      continue;
    }
    now_ = std::max(now_, t);
    update_temperatures(t);
    while (!planner_.empty() && head_end_ <= t) planner_step(head_end_);
    if (wait_ != Wait::None && wait_ != Wait::Heating && next_busy_ <= t) {
      send("echo:busy: processing");
      next_busy_ = t + kKeepalive;
    }
    if (next_report_ <= t) {
      bool heating = wait_ == Wait::Heating;
      std::string report = temperature_report();
      if (heating) report += " W:?";
      send(report);
      next_report_ = heating ? t + 1 : (autoreport_ > 0 ? t + autoreport_ : kNever);
    }
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
      send("Error:Printer halted. kill() called!");
      halted_ = true;
      return;
    }
  }
  // Marlin keeps one slot of its ring buffer free.
  if (rx_.size() - rx_head_ >= static_cast<std::size_t>(config_.rx_buffer - 1)) {
    ++stats_.overrun_bytes;
    return;
  }
  rx_ += c;
  // Between commands Marlin reads every byte as it comes (while its queue has
  // room), so a line longer than the RX buffer does not overrun an idle printer.
  if (wait_ == Wait::None) run(t);
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

std::string VirtualPrinter::temperature_report() const {
  return fmt::format("T:{:.2f} /{:.2f} B:{:.2f} /{:.2f} @:{} B@:{}", hotend_, hotend_target_, bed_, bed_target_,
                     hotend_ < hotend_target_ ? 127 : 0, bed_ < bed_target_ ? 127 : 0);
}

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
    parse_rx(t);
    if (queue_.empty()) return;
    start(t);
  }
}

void VirtualPrinter::parse_rx(double t) {
  // Marlin's get_serial_commands(): read while the queue has room.
  while (queue_.size() < static_cast<std::size_t>(config_.queue) && rx_head_ < rx_.size() && !halted_) {
    char c = rx_[rx_head_++];
    if (c == '\n' || c == '\r') {
      if (!partial_.empty()) {
        std::string line;
        line.swap(partial_);
        process_line(line, t);
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
}

void VirtualPrinter::line_error(const char* message, double t) {
  (void)t;
  send(fmt::format("Error:{}{}", message, last_n_));
  // Marlin drains its receive buffer after a bad line: whatever followed is
  // gone and must be resent too.
  stats_.drained_bytes += rx_.size() - rx_head_;
  rx_.clear();
  rx_head_ = 0;
  send(fmt::format("Resend: {}", last_n_ + 1));
  send("ok");
}

bool VirtualPrinter::process_line(std::string& line, double t) {
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
      line_error("Line Number is not Last Line Number+1, Last Line: ", t);
      return false;
    }
    std::size_t apos = line.rfind('*');
    if (apos == std::string::npos) {
      ++stats_.checksum_errors;
      line_error("No Checksum with line number, Last Line: ", t);
      return false;
    }
    long long sum = std::strtoll(line.c_str() + apos + 1, nullptr, 10);
    if (sum != checksum(std::string_view(line).substr(0, apos))) {
      ++stats_.checksum_errors;
      line_error("checksum mismatch, Last Line: ", t);
      return false;
    }
    if (chance(config_.resend)) {
      ++stats_.spurious_resends;
      line_error("checksum mismatch, Last Line: ", t);
      return false;
    }
    last_n_ = n;
    number = n;
    ++stats_.accepted_lines;
    text = command_for_sending(text);
  } else if (line.find('*') != std::string::npos) {
    ++stats_.checksum_errors;
    line_error("No Line Number with checksum, Last Line: ", t);
    return false;
  }
  Command cmd;
  if (!spare_.empty()) {
    cmd = std::move(spare_.back());
    spare_.pop_back();
  }
  cmd.text.assign(text);
  cmd.number = number;
  queue_.push_back(std::move(cmd));
  return true;
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
  queued_length_ += pending_length_;
  ++stats_.moves;
}

void VirtualPrinter::planner_step(double t) {
  planner_.pop_front();
  done_length_ += lengths_.front();
  lengths_.pop_front();
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
  if (!config_.advanced_ok) {
    send("ok");
    return;
  }
  // The queue still holds the command being acknowledged, as in Marlin.
  int planner_free = config_.planner - static_cast<int>(planner_.size());
  int queue_free = config_.queue - static_cast<int>(queue_.size());
  if (number >= 0) {
    send(fmt::format("ok N{} P{} B{}", number, planner_free, queue_free));
  } else {
    send(fmt::format("ok P{} B{}", planner_free, queue_free));
  }
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
  Move m = state_.apply(line);
  if (line.kind == CommandKind::Extended || line.kind == CommandKind::Host) {
    send(fmt::format("echo:Unknown command: \"{}\"", line.code()));
    finish(t);
    return;
  }
  if (m.kind == MoveKind::Linear || m.kind == MoveKind::Arc) {
    double length = m.length > 0 ? m.length : std::abs(m.filament);
    if (length > 0) {
      double feed = m.feedrate > 0 ? m.feedrate : 1500;
      pending_duration_ = config_.instant_moves ? 0 : length / (feed / 60);
      pending_length_ = m.length;
      if (planner_.size() >= static_cast<std::size_t>(config_.planner)) {
        wait_ = Wait::PlannerSlot;
        next_busy_ = t + kKeepalive;
        return;
      }
      add_block(pending_duration_, t);
    }
    finish(t);
    return;
  }
  if (line.is_g(28) || line.is_g(29) || line.is_g(4) || line.is_m(400)) {
    wait_ = Wait::PlannerEmpty;
    next_busy_ = t + kKeepalive;
    after_ = 0;
    if (line.is_g(28) || line.is_g(29)) {
      after_ = 1;
      after_duration_ = config_.instant_moves ? 0 : kHomingTime;
    } else if (line.is_g(4)) {
      after_ = 2;
      after_duration_ = line.value_or('P', 0) / 1000 + line.value_or('S', 0);
    }
    return;
  }
  if (line.is_m(104) || line.is_m(109)) hotend_target_ = line.value_or('S', line.value_or('R', hotend_target_));
  if (line.is_m(140) || line.is_m(190)) bed_target_ = line.value_or('S', line.value_or('R', bed_target_));
  if (line.is_m(109) || line.is_m(190)) {
    heating_bed_ = line.is_m(190);
    wait_ = Wait::Heating;
    waited_while_empty_ = true;
    next_report_ = std::min(next_report_, t + 1);
    return;
  }
  if (line.is_m(105)) {
    send(fmt::format("ok {}", temperature_report()));
    ok_sent_ = true;
  } else if (line.is_m(114)) {
    send(fmt::format("X:{:.2f} Y:{:.2f} Z:{:.2f} E:{:.2f} Count X:{} Y:{} Z:{}", state_.position[kX],
                     state_.position[kY], state_.position[kZ], state_.position[kE],
                     std::lround(state_.machine(kX) * 80), std::lround(state_.machine(kY) * 80),
                     std::lround(state_.machine(kZ) * 400)));
  } else if (line.is_m(110)) {
    if (line.find('N') != nullptr) last_n_ = static_cast<long long>(line.value_or('N', 0));
  } else if (line.is_m(115)) {
    std::string link = config_.report_link ? fmt::format(" TIME_SCALE:{} BAUD:{}", config_.time_scale, config_.baud)
                                           : std::string();
    send(fmt::format("FIRMWARE_NAME:Marlin 2.1.2 (gc-virtual-printer) SOURCE_CODE_URL:github.com/MarlinFirmware/Marlin "
                     "PROTOCOL_VERSION:1.0 MACHINE_TYPE:Virtual EXTRUDER_COUNT:1{}",
                     link));
    send("Cap:SERIAL_XON_XOFF:0");
    send(fmt::format("Cap:ADVANCED_OK:{}", config_.advanced_ok ? 1 : 0));
    send("Cap:EMERGENCY_PARSER:1");
    send("Cap:AUTOREPORT_TEMP:1");
    send("Cap:AUTOREPORT_POS:0");
    send("Cap:HOST_ACTION_COMMANDS:1");
    // Not a Marlin capability (Marlin does not report its MAX_CMD_SIZE); a
    // host that reads it can size its lines.
    send(fmt::format("Cap:MAX_CMD_SIZE:{}", config_.max_line));
  } else if (line.is_m(155)) {
    autoreport_ = line.value_or('S', 0);
    next_report_ = autoreport_ > 0 ? t + autoreport_ : (wait_ == Wait::Heating ? next_report_ : kNever);
  } else if (line.is_m(112)) {
    send("Error:Printer halted. kill() called!");
    halted_ = true;
    return;
  }
  finish(t);
}

bool VirtualPrinter::still_waiting(double t) {
  switch (wait_) {
    case Wait::None: return false;
    case Wait::PlannerSlot:
      if (planner_.size() >= static_cast<std::size_t>(config_.planner)) return true;
      add_block(pending_duration_, t);
      return false;
    case Wait::PlannerEmpty:
      if (!planner_.empty()) return true;
      if (after_ == 0) return false;
      wait_ = after_ == 1 ? Wait::Homing : Wait::Dwell;
      wait_until_ = t + after_duration_;
      waited_while_empty_ = true;
      after_ = 0;
      return t < wait_until_;
    case Wait::Dwell:
    case Wait::Homing:
    case Wait::Stall: return t < wait_until_;
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
  ++stats_.executed;
  if (log_ != nullptr) {
    std::fprintf(log_, "%.6f\t%lld\t%.3f\t%.3f\t%.3f\t%.5f\t%s\n", t, c.number, state_.position[kX],
                 state_.position[kY], state_.position[kZ], state_.position[kE], c.text.c_str());
  }
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
    send("Error:Thermal Runaway, system stopped! Heater_ID: 0");
    send("Error:Printer halted. kill() called!");
    halted_ = true;
  }
  if (done == config_.silent_after) silent_ = true;
  if (done == config_.disconnect_after) disconnected_ = true;
  spare_.push_back(std::move(c));
  queue_.pop_front();
  if (spare_.size() > 8) spare_.pop_front();
  wait_ = Wait::None;
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
