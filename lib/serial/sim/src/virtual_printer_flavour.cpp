// The virtual printer's firmware-specific ways (DialectBehaviour,
// virtual_dialect.hpp): Klipper's refusals (moves before homing, every
// command while shut down) and FIRMWARE_RESTART, Prusa's own pause (M601)
// and its waits for the user (M600, "M115 U<newer version>").
#include <algorithm>
#include <charconv>
#include <string>

#include "gcode/core/line.hpp"
#include "gcode/serial/sim/virtual_printer.hpp"

namespace gcode::serial {

namespace {

// What Klipper still does while shut down (its base_gcode_handlers).
bool works_while_shut_down(const Line& line) {
  if (line.kind == CommandKind::Extended) {
    std::string_view code = line.code();
    code = code.substr(0, code.find(' '));
    return code == "FIRMWARE_RESTART" || code == "RESTART" || code == "STATUS" || code == "HELP";
  }
  return line.is_m(105) || line.is_m(110) || line.is_m(112) || line.is_m(115);
}

// "3.13.3" against "3.11.0": whether `wanted` is newer than `have`, part by part.
bool newer_version(std::string_view wanted, std::string_view have) {
  auto next = [](std::string_view& v) {
    int n = 0;
    auto res = std::from_chars(v.data(), v.data() + v.size(), n);
    v.remove_prefix(static_cast<std::size_t>(res.ptr - v.data()));
    if (!v.empty() && v.front() == '.') v.remove_prefix(1);
    return n;
  };
  for (int i = 0; i < 3; ++i) {
    int w = next(wanted), h = next(have);
    if (w != h) return w > h;
  }
  return false;
}

}  // namespace

// A command the firmware answers with an error and its ok, without doing
// it: Klipper and RepRapFirmware refuse a move before homing ("!! Must
// home axis first", "Error: G0/G1: insufficient axes homed"), Klipper every
// command while shut down. Not in the executed log: it never ran.
bool VirtualPrinter::refused(const Line& line) {
  std::vector<std::string> answer;
  if (flavour_.shut_down() && !works_while_shut_down(line)) {
    answer = dialect_->refused_while_shut_down(flavour_.shutdown_reason());
  } else if (dialect_->behaviour().moves_need_homing && !homed_ && moves_axes(line)) {
    answer = {dialect_->not_homed(state_.position[kX], state_.position[kY], state_.position[kZ],
                                  state_.position[kE])};
  } else {
    return false;
  }
  for (const std::string& a : answer) send(a);
  drop_head();
  return true;
}

void VirtualPrinter::drop_head() {
  send_ok(queue_.front().number);
  spare_.push_back(std::move(queue_.front()));
  queue_.pop_front();
  wait_ = Wait::None;
}

bool VirtualPrinter::moves_axes(const Line& line) const {
  if (line.kind != CommandKind::Standard || line.letter != 'G' || line.number > 3) return false;
  MachineState probe = state_;
  Move m = probe.apply(line);
  return m.length > 0;
}

// Marlin's kill(): a last word, then silence. Klipper shuts down: motion
// stops, it says so, and answers every command with an error until
// FIRMWARE_RESTART (a command that was waiting is answered so too).
void VirtualPrinter::halt(std::string_view why) {
  if (halted_ || flavour_.shut_down()) return;
  send(dialect_->halted());
  if (!dialect_->behaviour().shutdown_answers) {
    halted_ = true;
    return;
  }
  flavour_.shut_down_for(why);
  planner_.clear();
  lengths_.clear();
  block_numbers_.clear();
  wait_ = Wait::None;
  after_ = After::Nothing;
}

// home-fails: the G28 under way ended without reaching its endstop. Marlin
// kills (VALIDATE_HOMING_ENDSTOPS), saying only that it halted; Klipper
// answers G28 with the error and its ok, unhomed.
void VirtualPrinter::fail_homing() {
  homing_fails_ = false;
  if (dialect_->behaviour().homing_failure_halts) {
    halt("Homing Failed");
  } else {
    send(dialect_->homing_failed());
  }
}

// Klipper's extended commands it knows; FIRMWARE_RESTART and RESTART
// restart it once their ok is out (the pseudo-terminal stays).
bool VirtualPrinter::process_extended(const Line& line) {
  std::string_view code = line.code();
  code = code.substr(0, code.find(' '));
  if (code == "FIRMWARE_RESTART" || code == "RESTART") flavour_.restart_after_ok();
  return true;
}

// M600 (Prusa): the filament change waits for the user, saying nothing.
bool VirtualPrinter::process_M600(double t) {
  if (!dialect_->behaviour().user_waits) return true;
  return wait_for_planner(t, After::User, config_.user_seconds);
}

// M601 (Prusa): answered at once (its ClearToSend), then the moves end, it
// parks, says "// action:paused", and holds every command until the user
// resumes ("// action:resumed").
bool VirtualPrinter::process_M601(double t) {
  if (!dialect_->behaviour().own_pause) return true;
  send_ok(queue_.front().number);
  ok_sent_ = true;
  return wait_for_planner(t, After::OwnPause, config_.user_seconds);
}

// "M115 U<version>" (Prusa): a version newer than its own shows an update
// message until the user confirms, for at most 30 s; otherwise just its ok.
bool VirtualPrinter::process_M115_version(const Line& line, double t) {
  if (!dialect_->behaviour().user_waits) return process_M115();
  std::string_view text = line.code();
  std::size_t u = text.find('U');
  if (!newer_version(text.substr(u + 1), dialect_->firmware_version())) return true;
  wait_ = Wait::User;
  wait_until_ = t + std::min(30.0, config_.user_seconds);
  return false;
}

// The user answered: the wait ends (its command's ok follows); an own
// pause says it resumed.
bool VirtualPrinter::end_user_wait() {
  if (flavour_.take_resume()) send(dialect_->resumed());
  return false;
}

}  // namespace gcode::serial
