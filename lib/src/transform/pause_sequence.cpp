#include "gcode/transform/pause_sequence.hpp"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "gcode/core/line_builder.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/text.hpp"
#include "gcode/transform/transition.hpp"

namespace gcode {

namespace {

// The user's own lines: written as they are, not followed.
void add_text_lines(Transition& t, std::string_view text) {
  for (const std::string& line : split_lines(text)) t.opaque(line);
}

struct Heater {
  int tool;
  double target;
};

std::vector<Heater> heaters(const MachineState& s, const PauseConfig& c) {
  std::vector<Heater> list;
  for (std::size_t t = 0; t < s.hotend_target.size(); ++t)
    if (s.hotend_target[t] > 0) list.push_back({static_cast<int>(t), s.hotend_target[t]});
  if (list.empty()) {
    if (c.resume_temp <= 0)
      throw std::invalid_argument(
          "no hotend temperature is set before this point, so none can be restored after the standby "
          "temperature: give the resume temperature");
    list.push_back({s.tool, c.resume_temp});
  } else if (c.resume_temp > 0) {
    for (Heater& h : list) h.target = c.resume_temp;
  }
  return list;
}

// The pause as it is built: what the pause half did that the resume undoes.
struct PauseRun {
  PauseRun(const MachineState& state, const PauseConfig& config)
      : s(state), c(config), z0(state.at(kZ)), file_fw_retracted(state.firmware_retracted) {}
  const MachineState& s;
  const PauseConfig& c;
  Fixed z0, safe, park_z;
  bool file_fw_retracted;
  bool we_fw = false;       // the pause retracted by firmware
  double we_e = 0;          // and by this much E
  bool block_relative_e = false;
  std::vector<Heater> heat;
  // Whether heater h's line names its tool.
  bool name_tool(const Heater& h) const { return heat.size() > 1 || h.tool != s.tool; }
};

// Retract, unless the file already did (a second retraction would be
// pushed back by nobody). Firmware retraction when the file uses it: a
// bare G10 while retracted is ignored by Marlin, so never two in a row.
void retract(Transition& t, const PausePoint& point, PauseRun& run) {
  const bool file_e_retracted = point.pending_retraction > 1e-9;
  if (run.c.retract <= 0 || run.file_fw_retracted || file_e_retracted) return;
  if (run.s.uses_firmware_retraction) {
    t.firmware_retraction(true);
    run.we_fw = true;
  } else {
    run.we_e = run.c.retract;
    t.extrude_mm(-run.we_e, run.c.retract_speed);
  }
}

// Lift above everything printed so far, never down, never past the top.
// Heights the block makes up are rounded to the file's Z decimals; the
// return goes to the file's own Z exactly.
void heights(const Transition& t, const PausePoint& point, const Precision& precision, PauseRun& run) {
  const PauseConfig& c = run.c;
  const int zd = precision.of('Z');
  run.safe = std::max(t.safe_z(std::max(run.z0, Fixed::from_double(point.top_z))), run.z0);
  run.park_z = run.safe;
  if (c.min_park_z > 0 && Fixed::from_double(c.min_park_z) > run.park_z)
    run.park_z = Fixed::from_double(c.max_z > 0 ? std::min(c.min_park_z, c.max_z) : c.min_park_z).rounded(zd);
  run.park_z = std::max(run.park_z, run.safe);
}

void wait(Transition& t, const PauseConfig& c) {
  switch (c.method) {
    case PauseMethod::M0:
    case PauseMethod::M1: {
      std::string w = c.method == PauseMethod::M0 ? "M0" : "M1";
      if (!c.message.empty()) w += " " + c.message;
      t.opaque(w);
      break;
    }
    case PauseMethod::Dwell: {
      LineBuilder b;
      b.start("G4").word('S', c.dwell_seconds, 3);
      t.opaque(b.view());
      break;
    }
    case PauseMethod::Custom: add_text_lines(t, c.custom_wait); break;
    case PauseMethod::None: break;
    default: t.opaque(pause_method_name(c.method)); break;
  }
}

// Standby, steppers, messages and the wait, the head parked.
void while_parked(Transition& t, PauseRun& run) {
  const PauseConfig& c = run.c;
  if (c.standby) {
    run.heat = heaters(run.s, c);
    for (const Heater& h : run.heat) t.hotend(h.tool, c.standby_temp, false, run.name_tool(h));
  }
  LineBuilder b;
  if (c.stepper_hold > 0) t.line(b.start("M84").word('S', c.stepper_hold, 0).view());
  const bool message_on_wait = c.method == PauseMethod::M0 || c.method == PauseMethod::M1;
  if (!c.message.empty() && !message_on_wait) t.opaque("M117 " + c.message);
  if (!c.host_message.empty()) t.opaque("M118 " + c.host_message);
  if (c.beep) t.line(b.start("M300").word('S', c.beep_hz, 0).word('P', c.beep_ms, 0).view());
  add_text_lines(t, c.before_wait);
  wait(t, c);
}

void write_pause(Transition& t, const PausePoint& point, const Precision& precision, PauseRun& run) {
  const PauseConfig& c = run.c;
  const MachineState& s = run.s;
  // The block moves in absolute XYZ. On Marlin G90 also makes E absolute, so
  // the file's E mode is set again right after it, if the file ever set one;
  // a file that never did keeps its mode untouched (issue 11) and the block
  // extrudes in the mode in force after the G90.
  if (s.relative_xyz) {
    t.line("G90");
    if (s.e_mode_set) t.line(s.relative_e ? "M83" : "M82");
  }
  run.block_relative_e = t.printer().relative_e;
  retract(t, point, run);
  heights(t, point, precision, run);
  if (run.park_z > run.z0) t.move_z(run.park_z);
  if (c.park)
    t.move_xy(Fixed::from_double(c.park_x).rounded(precision.of('X')),
              Fixed::from_double(c.park_y).rounded(precision.of('Y')));
  if (c.wait_for_moves) t.line("M400");
  // Unload while the nozzle is still at printing temperature.
  t.extrude_mm(-c.unload, c.unload_speed);
  while_parked(t, run);
}

void write_resume(Transition& t, const PausePoint& point, const PauseRun& run) {
  const PauseConfig& c = run.c;
  const MachineState& s = run.s;
  add_text_lines(t, c.after_wait);
  if (c.standby)
    for (const Heater& h : run.heat) t.hotend(h.tool, h.target, c.wait_for_heat, run.name_tool(h));
  t.extrude_mm(c.reload, c.reload_speed);
  if (c.purge > 0 || c.prime > 0) {
    // Cura's order: push back what is retracted, purge and prime, then take
    // the same retraction again so the return travel does not string and the
    // file's own unretract (or ours) finds the nozzle as it left it.
    const double in_effect = point.pending_retraction + run.we_e;
    const bool fw_in_effect = run.file_fw_retracted || run.we_fw;
    if (fw_in_effect) t.firmware_retraction(false);
    t.extrude_mm(in_effect, c.unretract_speed);
    t.extrude_mm(c.purge, c.purge_speed);
    t.extrude_mm(c.prime, c.prime_speed);
    t.extrude_mm(-in_effect, c.retract_speed);
    if (fw_in_effect) t.firmware_retraction(true);
  }
  if (c.park) {
    if (run.park_z > run.safe) t.move_z(run.safe);
    t.move_xy(s.at(kX), s.at(kY));
  }
  if (run.park_z != run.z0) t.move_z(run.z0);
  t.extrude_mm(run.we_e, c.unretract_speed);
  if (run.we_fw) t.firmware_retraction(false);
  if (s.relative_xyz) t.line("G91");
  // Custom lines or the firmware's own pause routine may have changed it;
  // never written into a file that does not set it itself.
  if (s.e_mode_set) t.line(s.relative_e ? "M83" : "M82");
  // Absolute E: the file's next E word is a coordinate. Relative E after an
  // unload/purge: a later switch to M82 (Cura appends one to its end code)
  // would otherwise start from a shifted coordinate.
  if (!s.relative_e || run.block_relative_e != s.relative_e || !t.net_filament().is_zero())
    t.e_coordinate(s.at(kE), true);
  t.feed_rate(s.feedrate, true);
}

}  // namespace

bool parse_pause_method(std::string_view text, PauseMethod& method, std::string& custom_text) {
  struct Name {
    const char* name;
    PauseMethod method;
  };
  static constexpr Name kNames[] = {
      {"M0", PauseMethod::M0},     {"M1", PauseMethod::M1},         {"M25", PauseMethod::M25},
      {"M125", PauseMethod::M125}, {"M226", PauseMethod::M226},     {"M600", PauseMethod::M600},
      {"M601", PauseMethod::M601}, {"@pause", PauseMethod::HostPause}, {"PAUSE", PauseMethod::Klipper},
      {"G4", PauseMethod::Dwell},  {"none", PauseMethod::None},
  };
  for (const Name& n : kNames) {
    if (iequals(text, n.name)) {
      method = n.method;
      return true;
    }
  }
  constexpr std::string_view kCustom = "custom:";
  if (text.size() > kCustom.size() && iequals(text.substr(0, kCustom.size()), kCustom)) {
    method = PauseMethod::Custom;
    custom_text = std::string(text.substr(kCustom.size()));
    return true;
  }
  return false;
}

std::string_view pause_method_name(PauseMethod method) {
  switch (method) {
    case PauseMethod::M0: return "M0";
    case PauseMethod::M1: return "M1";
    case PauseMethod::M25: return "M25";
    case PauseMethod::M125: return "M125";
    case PauseMethod::M226: return "M226";
    case PauseMethod::M600: return "M600";
    case PauseMethod::M601: return "M601";
    case PauseMethod::HostPause: return "@pause";
    case PauseMethod::Klipper: return "PAUSE";
    case PauseMethod::Dwell: return "G4";
    case PauseMethod::Custom: return "custom";
    case PauseMethod::None: return "none";
  }
  return "?";
}

PauseBlock build_pause(const PausePoint& point, const PauseConfig& c) {
  const MachineState& s = point.state;
  if (s.inches)
    throw std::invalid_argument("the file is in inches (G20) here; pausing is only supported in millimetres");
  if (!s.known[kX] || !s.known[kY] || !s.known[kZ])
    throw std::invalid_argument("the head position is not known here (no homing or absolute move yet)");

  PauseBlock block;
  const Precision defaults;
  const Precision& precision = point.precision != nullptr ? *point.precision : defaults;
  PauseRun run(s, c);
  Transition t(s, precision, block.pause,
               {.lift = c.lift, .max_z = c.max_z, .z_feed = c.z_speed * 60, .xy_feed = c.travel_speed * 60,
                .g0 = false});
  write_pause(t, point, precision, run);
  t.write_to(block.resume);
  write_resume(t, point, run);
  block.safe_z = run.safe.to_double();
  block.park_z = run.park_z.to_double();
  block.net_filament = t.net_filament().to_double();
  return block;
}

}  // namespace gcode
