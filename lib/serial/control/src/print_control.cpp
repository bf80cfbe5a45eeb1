#include "gcode/serial/control/print_control.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/core/line.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/placeholders.hpp"
#include "gcode/core/text.hpp"
#include "gcode/transform/custom_gcode.hpp"
#include "gcode/transform/transition.hpp"
#include "gcode/serial/protocol/protocol.hpp"

namespace gcode::serial {

namespace {

SpeedOptions speed_options(double factor, bool travel, const PrintControlConfig& c) {
  SpeedOptions o;
  o.factor = factor;
  o.travel = travel;
  o.max_speed = c.max_speed;
  o.max_flow = c.max_flow;
  o.filament_diameter = c.filament_diameter;
  o.mark.clear();  // comments do not reach the printer
  return o;
}

// What a block without a park position did: `note` (ParkRules::place_or_lift)
// and how high it got, from `z`, and why no higher where the printer's
// height stopped it.
std::string unparked(std::string_view note, double z, double lifted_to, double max_z) {
  std::string text = fmt::format("{}: lifted from Z{} to Z{}", note, z, lifted_to);
  if (max_z > 0 && lifted_to >= max_z - 1e-9) text += fmt::format(" (the printer's height, Z{}, stops it there)", max_z);
  return text;
}

}  // namespace

std::string_view print_state_name(PrintState state) {
  switch (state) {
    case PrintState::Printing: return "printing";
    case PrintState::Pausing: return "pausing";
    case PrintState::Paused: return "paused";
    case PrintState::Cancelling: return "cancelling";
  }
  return "?";
}

PrintControl::PrintControl(const PrintControlConfig& config, Sender& sender, Diagnostics& diagnostics,
                           const Precision& precision)
    : config_(config),
      sender_(sender),
      diag_(diagnostics),
      precision_(precision),
      user_speed_(speed_options(1, true, config), precision),
      rush_(speed_options(std::max(1.0, config.rush), false, config), precision),
      objects_(diagnostics, precision) {
  config_.pause.method = PauseMethod::None;
  objects_.exclude(config_.exclude, "--exclude");
  user_speed_.set_enabled(false);
  rush_.set_enabled(false);
}

void PrintControl::add_stages(Pipeline& pipeline, std::uint64_t line_offset, int resumed_layer) {
  // First: what the excluder writes to catch up is sped up like the rest.
  objects_.add_stage(pipeline, line_offset, resumed_layer);
  pipeline.add(user_speed_);
  pipeline.add(rush_);
}

std::string_view PrintControl::state_label() const {
  if (state_ == PrintState::Paused && pauses_.reaching()) return "pausing";
  return print_state_name(state_);
}

void PrintControl::line(const TrackedLine& t, double now) {
  now_ = now;
  const Line& line = t.line;
  region_ = t.region;
  if (t.layer > 0) layer_ = t.layer;
  printed_before_line_ = printed_;
  printed_.observe(t);
  bool host_pause = false;
  if (line.kind == CommandKind::None && !line.malformed) {
    // ";@pause": a comment only for the slicer, a pause for the host.
    if (!iequals(line.comment_text(), "@pause")) return;
    host_pause = true;
  } else if (line.kind == CommandKind::Host) {
    ++host_commands_;
    if (!iequals(line.code(), "@pause")) {
      diag_.info(fmt::format("line {}: host command '{}' not sent to the printer", t.raw.number, line.code()));
      return;
    }
    host_pause = true;
  } else if (line.letter == 'M' && std::find(config_.pause_on.begin(), config_.pause_on.end(), line.number) !=
                                       config_.pause_on.end()) {
    ++host_commands_;
    host_pause = true;
  }
  std::string_view command;
  if (!host_pause) {
    command = command_for_sending(line, scratch_);
    if (command.empty()) return;
    if (line.is_m(110)) {
      diag_.warn(t.raw.number, "M110 not sent: gc-send numbers the lines itself");
      return;
    }
  }
  process(command, t.raw.number, t.layer, t.state, host_pause, t.move.extruding);
}

void PrintControl::process(std::string_view command, std::uint64_t source, int layer, const MachineState& after,
                           bool host_pause, bool extruding) {
  if (holding_) {
    if (state_ == PrintState::Cancelling) return;
    held_.push_back(Held{std::string(command), source, layer, after, host_pause, extruding});
    return;
  }
  if (host_pause) {
    last_source_ = source;
    hold_here(fmt::format("the file's pause at line {}", source));
    return;
  }
  forget_sent();
  ledger_.handed({handed_, printed_before_line_, source, layer, sender_.last_submitted() + 1});
  sender_.submit(command, source, layer);
  handed_ = after;
  last_source_ = source;
  if (extruding) sent_extrusion_ = true;
}

void PrintControl::layer(const LayerInfo& info, const MachineState& before, double now) {
  now_ = now;
  // A swap asked for goes first, unless a pause does (the swap then comes
  // at its resume).
  if (swap_ && state_ == PrintState::Printing && !holding_ && swap_here(before, printed_, info.index - 1)) return;
  layer_ = info.index;
  region_ = Region::Layer;
  sent_extrusion_ = false;
  if (state_ != PrintState::Pausing) return;
  pauses_.current().paused_before_layer = info.index;
  finish_pausing(before);
}

void PrintControl::end_code(const MachineState& before, double now) {
  now_ = now;
  // The file is done but for its end code: the other file goes on on top.
  if (swap_ && state_ == PrintState::Printing && !holding_ && swap_here(before, printed_, layer_)) return;
  region_ = Region::EndCode;
  if (state_ == PrintState::Pausing) finish_pausing(before);
}

void PrintControl::end_of_input(double now) {
  now_ = now;
  input_ended_ = true;
  // A file cut short (no next layer, no end code): the pause goes at its end.
  if (state_ == PrintState::Pausing) finish_pausing(handed_);
}

// The layer asked to be finished is: the rush ends, the pause goes here.
void PrintControl::finish_pausing(const MachineState& at) {
  rush_.set_enabled(false);
  pause_here(at);
}

PauseRecord& PrintControl::start_record(std::string request) {
  PauseRecord& r = pauses_.start(std::move(request), layer_, now_, probe_.now ? probe_.now() : -1);
  if (probe_.now) diag_.info(fmt::format("{}: asked at printer time {:.6f} s", r.request, r.printer_request));
  return r;
}

void PrintControl::request_pause(std::string request, bool now) {
  if (state_ == PrintState::Cancelling) return;
  if (state_ == PrintState::Pausing && now) {
    // Escalated: no need to finish the layer any more.
    withdraw_unsent();
    finish_pausing(handed_);
    return;
  }
  if (state_ != PrintState::Printing) {
    diag_.info(fmt::format("{}: already {}", request, state_label()));
    return;
  }
  PauseRecord& r = start_record(request);
  if (probe_.travelled && r.printer_request >= 0) r.path_at_request = probe_.travelled(r.printer_request);
  if (now || region_ == Region::EndCode) {
    withdraw_unsent();
    pause_here(handed_);
    return;
  }
  state_ = PrintState::Pausing;
  if (region_ == Region::Layer && config_.rush > 1) {
    rush_.set_enabled(true);
    diag_.info(fmt::format("{}: finishing layer {} at {:g} times the speed (after input line {})", request, layer_,
                           config_.rush, last_source_));
  } else {
    diag_.info(fmt::format("{}: pausing before layer 1", request));
  }
}

// Commands handed to the sender but not on their way yet go after the pause
// block: they become the first held lines, and the stream's state and the
// pause context go back to before them.
void PrintControl::withdraw_unsent() {
  // Only the commands of the file since the last block are known here.
  forget_sent();
  std::size_t n = std::min(ledger_.size(), sender_.pending());
  if (!can_rewind(n)) return;
  std::vector<std::string> commands;
  if (sender_.withdraw_unsent(n, ledger_.entries()[ledger_.size() - n].before, commands) != n) return;
  const MachineState after_all = handed_;
  std::vector<TakeBackLedger::Entry> taken = rewind(n);
  std::deque<Held> back;
  for (std::size_t i = 0; i < n; ++i) {
    const MachineState& after = i + 1 < n ? taken[i + 1].before : after_all;
    back.push_back(Held{commands[i], taken[i].source, taken[i].layer, after, false});
  }
  for (auto it = held_.begin(); it != held_.end(); ++it) back.push_back(std::move(*it));
  held_.swap(back);
  diag_.info(fmt::format("pause now: {} commands not sent yet go after the pause", n));
}

// What the sender has sent can no longer be taken back.
void PrintControl::forget_sent() {
  ledger_.keep_unsent(sender_.pending());
}

// Lines of its own go to the sender: what came before them cannot be taken
// back over them.
void PrintControl::forget_recent() { ledger_.own_lines(last_source_); }

// Whether the last `n` commands handed to the sender are the file's, unsent.
bool PrintControl::can_rewind(std::size_t n) {
  forget_sent();
  return ledger_.can_take_back(n, sender_.pending());
}

// The stream's state and the pause context go back to before the last `n`
// commands handed to the sender (can_rewind(n)); returns their entries.
std::vector<TakeBackLedger::Entry> PrintControl::rewind(std::size_t n) {
  std::vector<TakeBackLedger::Entry> taken = ledger_.take_back(n);
  handed_ = taken.front().before;
  printed_ = taken.front().context;
  last_source_ = ledger_.last_source();
  return taken;
}

// The pause's options with {layer} and {z} filled in for a stop at `at`.
PauseConfig PrintControl::pause_config(const MachineState& at) const {
  PauseConfig c = config_.pause;
  char zt[kMaxNumberChars];
  Placeholders values{{"layer", std::to_string(std::max(layer_, 1))}, {"z", std::string(number_text(at.position[kZ], 3, zt))}};
  for (std::string* text : {&c.message, &c.host_message, &c.before_wait, &c.after_wait})
    *text = expand_placeholders(*text, values);
  // A Klipper without a display refuses M117 ('// Unknown command:"M117"').
  if (std::string_view(sender_.flavour().name) == "klipper") c.message.clear();
  return c;
}

void PrintControl::pause_here(const MachineState& at) {
  PauseRecord& r = pauses_.current();
  PauseConfig c = pause_config(at);
  PauseBlock block;
  std::string note;
  try {
    note = config_.park.place_or_lift(printed_, precision_, c);
    block = build_pause(printed_.point(at, &precision_), c);
  } catch (const std::exception& e) {
    diag_.warn(0, fmt::format("{}: cannot park ({}); holding the print where it is", r.request, e.what()));
    hold_here(r.request);
    return;
  }
  if (!note.empty())
    diag_.warn(0, fmt::format("{}: {}", r.request, unparked(note, at.position[kZ], block.park_z, c.max_z)));
  r.input_line = last_source_;
  r.block_number = sender_.last_submitted() + 1;
  r.block = true;
  if (probe_.watch) probe_.watch(r.block_number);
  MachineState parked = at;
  for (const std::string& l : block.pause) track(l, parked);
  // Paused before the block is numbered: the journal's records of it say
  // so, and a resume goes back into the pause.
  stop_at(at, parked, true);
  stop_.resume_lines = std::move(block.resume);
  submit_lines(block.pause, layer_);
  diag_.info(fmt::format("{}: pause block sent after input line {} (asked in layer {}); waiting for resume",
                         r.request, last_source_, r.layer));
}

void PrintControl::hold_here(std::string request) {
  if (state_ == PrintState::Printing || pauses_.empty()) start_record(std::move(request));
  PauseRecord& r = pauses_.current();
  r.input_line = last_source_;
  r.block_number = sender_.last_submitted() + 1;
  stop_at(handed_, handed_, false);
  diag_.info(fmt::format("{}: holding after input line {} (layer {}); waiting for resume", r.request, last_source_,
                         layer_));
}

// The print stops with the stream `at`; the resume starts from `resume_from`.
void PrintControl::stop_at(const MachineState& at, const MachineState& resume_from, bool own_block) {
  stop_.at = at;
  stop_.printed = printed_;
  stop_.resume_from = resume_from;
  stop_.printer = resume_from;
  stop_.resume_lines.clear();
  stop_.own_block = own_block;
  holding_ = true;
  state_ = PrintState::Paused;
}

void PrintControl::submit_lines(const std::vector<std::string>& lines, int layer) {
  forget_recent();  // the newest commands are no longer the file's
  sender_.reopen_input();  // the file may have ended: these are not the file's
  for (const std::string& l : lines) sender_.submit(l, 0, layer);
}

// A command of the user's while paused: followed, so the resume returns
// exactly.
void PrintControl::submit_typed(std::string_view command) {
  forget_recent();
  sender_.reopen_input();
  sender_.submit(command, 0, layer_);
  track(command, stop_.printer);
}

void PrintControl::track(std::string_view text, MachineState& state) const {
  Line l = Line::parse(text);
  state.apply(l);
}

// Lines that take the printer from `from` (where the commands typed while
// paused left it) back to `to` (where the resume starts): the position
// reached at a safe height, then the same modes, E coordinate, hot-end
// temperatures and feed rate. Transition's steps, in the put-back's order:
// the bed is left as the user set it, a hot end only where it has a target.
std::vector<std::string> PrintControl::put_back(const MachineState& from, const MachineState& to) const {
  std::vector<std::string> out;
  TransitionMoves moves;
  moves.lift = config_.pause.lift;
  moves.z_feed = config_.pause.z_speed * 60;
  moves.xy_feed = config_.pause.travel_speed * 60;
  moves.g0 = false;
  Transition t(from, precision_, out, moves);
  bool moved = false;
  for (int a : {kX, kY, kZ})
    if (to.known[static_cast<std::size_t>(a)] && from.at(a) != to.at(a)) moved = true;
  if (moved) {
    t.positioning(false);
    const Fixed high = std::max({from.at(kZ), to.at(kZ), t.safe_z(Fixed::from_double(printed_.top_z()))});
    if (high != from.at(kZ)) t.move_z(high);
    t.move_xy(to.at(kX), to.at(kY));
    if (high != to.at(kZ)) t.move_z(to.at(kZ));
  }
  t.positioning(to.relative_xyz);
  t.e_mode(to.relative_e);
  t.e_coordinate(to.at(kE));
  for (std::size_t h = 0; h < to.hotend_target.size(); ++h) {
    const double target = to.hotend_target[h];
    if (t.printer().hotend_target[h] == target || target <= 0) continue;
    t.hotend(static_cast<int>(h), target, true, static_cast<int>(h) != t.printer().tool);
  }
  t.feed_rate(to.feedrate);
  return out;
}

void PrintControl::resume() {
  if (state_ == PrintState::Pausing) {
    rush_.set_enabled(false);
    state_ = PrintState::Printing;
    pauses_.call_off();
    diag_.info("resume: the pause asked for is called off");
    return;
  }
  if (state_ != PrintState::Paused) {
    diag_.info("resume: not paused");
    return;
  }
  std::vector<std::string> lines = put_back(stop_.printer, stop_.resume_from);
  if (!lines.empty())
    diag_.info(fmt::format("resume: {} lines put back what the commands typed while paused changed", lines.size()));
  if (stop_.own_block) lines.insert(lines.end(), stop_.resume_lines.begin(), stop_.resume_lines.end());
  submit_lines(lines, layer_);
  stop_.resume_lines.clear();
  pauses_.resumed(now_);
  state_ = PrintState::Printing;
  holding_ = false;
  if (swap_ && at_layer_start()) {
    // Back where it paused, as if it never had: the other file joins there
    // (the held lines, observed after the pause point, are left out).
    if (swap_here(stop_.at, stop_.printed, std::max(0, layer_ - 1))) return;
  }
  diag_.info(fmt::format("resume: printing on from input line {}", last_source_ + 1));
  std::deque<Held> pending;
  pending.swap(held_);
  for (const Held& h : pending) process(h.command, h.source, h.layer, h.after, h.host_pause, h.extruding);
}

// `move_away`: retract, lift and park first (not when the printer cannot move).
void PrintControl::cancel(bool move_away) {
  if (state_ == PrintState::Cancelling) return;
  bool parked = !move_away || (state_ == PrintState::Paused && stop_.own_block);
  rush_.set_enabled(false);
  held_.clear();
  if (swap_) diag_.info(fmt::format("cancel: swap {} called off", swap_->path()));
  swap_.reset();
  // Nothing more of the file: what the sender holds unsent would otherwise
  // go out before the safe end (a long read-ahead, a start code). They are
  // left out and the park starts from before them, from the last command on
  // its way; lines of gc-send's own among them (a resume block) go out
  // first, and the park follows them.
  const std::size_t unsent = sender_.pending();
  if (state_ != PrintState::Paused && unsent > 0) {
    if (can_rewind(unsent)) {
      rewind(unsent);
      sender_.discard_unsent();
      diag_.info(fmt::format("cancel: {} commands not sent yet are left out", unsent));
    } else {
      diag_.info(fmt::format("cancel: {} commands not sent yet go out first", unsent));
    }
  }
  std::vector<std::string> lines = safe_end(state_ == PrintState::Paused ? stop_.printer : handed_, parked);
  state_ = PrintState::Cancelling;
  holding_ = true;
  submit_lines(lines, layer_);
  sender_.end_of_input();
  if (!move_away) return;
  diag_.error(fmt::format("cancelled after input line {} (layer {}): {}", last_source_, layer_,
                          parked ? "heaters and motors off" : "retract, lift, park, heaters and motors off"));
}

void PrintControl::lost(std::string_view why, double now) {
  if (state_ == PrintState::Cancelling) return;  // its safe end is on its way
  now_ = now;
  cancel(false);
  diag_.error(fmt::format("{}: the print stops after input line {} (layer {}); heaters and motors off", why,
                          last_source_, layer_));
}

// A cancel's end from `at`: retract, lift and park (unless `parked` by a
// pause block already), then the cancel G-code (heaters and motors off).
std::vector<std::string> PrintControl::safe_end(const MachineState& at, bool parked) {
  std::vector<std::string> lines;
  if (!parked) {
    PauseConfig c = config_.pause;
    c.standby = false;
    c.message.clear();
    c.host_message.clear();
    c.before_wait.clear();
    c.unload = 0;
    c.beep = false;
    c.stepper_hold = 0;
    try {
      std::string note = config_.park.place_or_lift(printed_, precision_, c);
      PauseBlock block = build_pause(printed_.point(at, &precision_), c);
      lines = std::move(block.pause);
      if (!note.empty()) diag_.warn(0, "cancel: " + unparked(note, at.position[kZ], block.park_z, c.max_z));
    } catch (const std::exception& e) {
      diag_.warn(0, fmt::format("cancel: cannot park ({}); heaters and motors off where the head is", e.what()));
    }
  }
  for (std::string& l : split_lines(config_.cancel_gcode)) lines.push_back(std::move(l));
  return lines;
}

std::size_t PrintControl::resume_into_pause(const MachineState& at, const MachineState& parked, double retracted,
                                            double top_z, std::size_t taken, double now) {
  now_ = now;
  PauseRecord& r = start_record("the journal's pause");
  r.input_line = last_source_;
  r.block_number = sender_.last_submitted() + 1;
  r.block = true;
  handed_ = at;
  PauseReentry reentry(at, retracted, top_z, &precision_, parked, taken);
  bool rest = false;
  try {
    PauseConfig c = pause_config(at);
    config_.park.place_or_lift(printed_, precision_, c);
    rest = reentry.finish_block(c);
  } catch (const std::exception& e) {
    reentry.cannot_make(e.what());
  }
  if (!reentry.warning().empty()) diag_.warn(0, "the journal's pause: " + reentry.warning());
  if (!rest) reentry.park_here(pause_config(at));
  stop_at(at, reentry.resume_from(), true);
  stop_.resume_lines = std::move(reentry.resume_lines());
  if (!rest) {
    stop_.printer = parked;
    diag_.info("the print was paused: waiting for resume");
    return 0;
  }
  submit_lines(reentry.rest(), layer_);
  diag_.info(fmt::format("the print was pausing: the rest of the pause block ({} of {} lines) sent; waiting for resume",
                         reentry.rest().size(), reentry.block_lines()));
  return reentry.rest().size();
}

double PrintControl::paused_seconds(double now) const {
  return pauses_.paused_seconds(now, state_ == PrintState::Paused);
}

bool PrintControl::interrupt() {
  ++interrupts_;
  if (interrupts_ > 1) return false;
  diag_.error("interrupted: cancelling (safe end); press Ctrl-C again for an emergency stop (M112)");
  cancel();
  return true;
}

void PrintControl::user_gcode(const std::string& text) {
  if (state_ != PrintState::Paused) {
    diag_.warn(0, fmt::format("gcode '{}': only while paused (now {})", text, state_label()));
    return;
  }
  Line line = Line::parse(text);
  std::string_view command = command_for_sending(line, scratch_);
  if (command.empty() || line.kind == CommandKind::Host || line.is_m(110)) {
    diag_.warn(0, fmt::format("gcode '{}': not a command for the printer", text));
    return;
  }
  submit_typed(command);
  ++user_commands_;
  diag_.info(fmt::format("gcode: {} sent", command));
}

// insert FILE: its commands go out while paused, followed like typed ones,
// so the resume still returns exactly (a structure printed on the top
// surface, a purge somewhere else).
void PrintControl::insert_file(const std::string& path) {
  if (state_ != PrintState::Paused) {
    diag_.warn(0, fmt::format("insert {}: only while paused (now {})", path, state_label()));
    return;
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    diag_.warn(0, fmt::format("insert {}: no such file", path));
    return;
  }
  std::string text;
  try {
    text = load_custom_gcode(path);
  } catch (const std::exception& e) {
    diag_.warn(0, fmt::format("insert {}: {}", path, e.what()));
    return;
  }
  std::size_t sent = 0;
  for (const std::string& l : split_lines(text)) {
    Line line = Line::parse(l);
    if (line.kind == CommandKind::None || line.kind == CommandKind::Host || line.is_m(110)) continue;
    std::string_view command = command_for_sending(line, scratch_);
    if (command.empty()) continue;
    submit_typed(command);
    ++sent;
  }
  user_commands_ += sent;
  diag_.info(fmt::format("insert {}: {} commands sent; resume returns to the print", path, sent));
}

void PrintControl::set_speed(double factor) {
  speed_ = factor;
  user_speed_.change_factor(factor);
  user_speed_.set_enabled(factor != 1);
  diag_.info(fmt::format("speed: following moves at {:g} times the file's", factor));
}

// Nothing of the current layer has gone out (its start, or the start code):
// a swap can take its place.
bool PrintControl::at_layer_start() const { return !sent_extrusion_; }

// swap FILE: checked now (readable, layers above what is printed, the same
// place on the bed), joined at the next layer's start or at the resume.
void PrintControl::request_swap(const std::string& path) {
  if (state_ == PrintState::Cancelling) return;
  if (!on_swap) {
    diag_.warn(0, fmt::format("swap {}: not possible here", path));
    return;
  }
  const bool paused = state_ == PrintState::Paused;
  std::unique_ptr<JoinStream> next;
  try {
    next = std::make_unique<JoinStream>(path);
    next->plan((paused ? stop_.printed : printed_).stream_point(paused ? stop_.at : handed_), precision_.of('Z'),
               "the print", nullptr);
  } catch (const std::exception& e) {
    diag_.warn(0, fmt::format("swap {}: {}; the print goes on as it is", path, e.what()));
    return;
  }
  if (swap_) diag_.info(fmt::format("swap {}: instead of {}", path, swap_->path()));
  swap_ = std::move(next);
  diag_.info(fmt::format("swap {}: {}", path,
                         paused && at_layer_start() ? "joins where the print paused, at the resume"
                         : paused                   ? "joins at the next layer's start after the resume"
                                                    : "joins at the next layer's start"));
}

// The other file goes on from here: `at` is where the printer stands (the
// current file's state after everything handed over), `context` what was
// printed up to there, `layers_done` the layers printed. False (the print
// goes on as it is, nothing changed) when it cannot join.
bool PrintControl::swap_here(const MachineState& at, const PauseContext& context, int layers_done) {
  std::unique_ptr<JoinStream> next = std::move(swap_);
  StreamPoint printed = context.stream_point(at);
  char zt[kMaxNumberChars];
  std::string top(number_text(printed.top_z, 3, zt));
  try {
    next->plan(printed, precision_.of('Z'), fmt::format("the print's layer {} (Z {})", layers_done, top), &diag_);
  } catch (const std::exception& e) {
    diag_.warn(0, fmt::format("swap {}: {}; the print goes on as it is", next->path(), e.what()));
    return false;
  }
  for (const std::string& r : next->report()) diag_.info(fmt::format("swap: {}", r));
  diag_.info(fmt::format("swap {}: joined onto layer {} (Z {}) after input line {}", next->path(), layers_done, top,
                         last_source_));
  ++swaps_;
  handed_ = at;
  printed_ = context;
  held_.clear();
  forget_recent();  // what went out last is no longer the input's
  layer_ = layers_done;
  on_swap(std::move(next), layers_done);
  return true;
}

void PrintControl::command(const ControlCommand& c, double now) {
  now_ = now;
  if (c.verb == nullptr) {
    diag_.warn(0, fmt::format("control: {}", c.argument));
    return;
  }
  c.verb->handle(*this, c);
}

void PrintControl::action(std::string_view text, double now) {
  now_ = now;
  auto starts = [&](std::string_view word) { return text.rfind(word, 0) == 0; };
  if (starts("pause") && !starts("paused")) {
    request_pause("//action:pause", false);
  } else if (starts("resume") && !starts("resumed")) {
    resume();
  } else if (starts("cancel")) {
    cancel();
  } else if (starts("paused") || starts("resumed")) {
    // The printer's own pause (Prusa): the sender holds its lines meanwhile
    // and has said so.
  } else {
    diag_.info(fmt::format("printer action: {}", text));
  }
}

void PrintControl::update(double now) {
  if (pauses_.empty()) return;
  PauseRecord& r = pauses_.current();
  if (state_ == PrintState::Paused && r.wall_paused < 0 && sender_.idle()) {
    pauses_.reached(now);
    diag_.info(fmt::format("paused (layer {}, {:.2f} s after the request); waiting for resume", r.layer,
                           now - r.wall_request));
    if (on_status) on_status();
  }
  if (r.latency_s < 0 && r.block && r.path_at_request >= 0 && probe_.watched) {
    double end = 0, queued = 0;
    if (probe_.watched(end, queued)) {
      r.latency_s = std::max(0.0, end - r.printer_request);
      r.latency_mm = std::max(0.0, queued - r.path_at_request);
    }
  }
}

}  // namespace gcode::serial
