#include "gcode/transform/pause_sequence.hpp"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "gcode/core/line_builder.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/text.hpp"

namespace gcode {

namespace {

// A value the block computes (E - 2, Z + lift, a park position), written
// with at most the input's decimals for its letter: 5.0348 - 2 is 3.0348.
std::string text_of(Fixed value, int decimals) {
  char buffer[kMaxNumberChars];
  return std::string(buffer, value.format(decimals, buffer));
}

// A position the file is at, written back exactly (its decimals are the
// file's own, so nothing is rounded).
std::string exact_text(Fixed value) { return text_of(value, Fixed::kDecimals); }

void add_text_lines(std::vector<std::string>& out, std::string_view text) {
  for (std::string& line : split_lines(text)) out.push_back(std::move(line));
}

// Writes the E moves of a block in the file's own E mode, at the file's E
// precision, keeping the E coordinate the firmware will hold exactly.
class Extruder {
 public:
  Extruder(bool relative, Fixed start, const Precision& precision)
      : relative_(relative), e_(start), decimals_(precision.of('E')), feed_decimals_(precision.of('F')) {}

  void move(std::vector<std::string>& out, double amount_mm, double speed_mm_s) {
    Fixed amount = Fixed::from_double(amount_mm).rounded(decimals_);
    if (amount.is_zero()) return;
    // Chunks keep each E move under the firmware's lengthy-extrude guard;
    // whole 150 mm pieces then the rest, so every piece is a short decimal.
    const Fixed chunk = Fixed::from_int(static_cast<std::int64_t>(kMaxExtrudeChunk));
    Fixed left = amount;
    while (!left.is_zero()) {
      Fixed piece = left > chunk ? chunk : (left < -chunk ? -chunk : left);
      left -= piece;
      LineBuilder b;
      b.start("G1");
      if (relative_) {
        b.text(" E").text(text_of(piece, decimals_));
      } else {
        e_ += piece;
        b.text(" E").text(text_of(e_, decimals_));
      }
      net_ += piece;
      b.word('F', speed_mm_s * 60, feed_decimals_);
      out.emplace_back(b.view());
    }
  }
  double net() const { return net_.to_double(); }
  bool pushed() const { return !net_.is_zero(); }

 private:
  bool relative_;
  Fixed e_;
  int decimals_;
  int feed_decimals_;
  Fixed net_;
};

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

std::string temperature_line(const char* command, const Heater& h, bool name_tool, char letter, double t) {
  LineBuilder b;
  b.start(command);
  if (name_tool) b.word('T', h.tool, 0);
  b.word(letter, t, 1);
  return std::string(b.view());
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
  auto& p = block.pause;
  auto& r = block.resume;
  const Precision defaults;
  const Precision& precision = point.precision != nullptr ? *point.precision : defaults;
  const Fixed z0 = s.at(kZ);
  const std::string e_mode = s.relative_e ? "M83" : "M82";
  // The block moves in absolute XYZ. On Marlin G90 also makes E absolute, so
  // the file's E mode is set again right after it, if the file ever set one;
  // a file that never did keeps its mode untouched (issue 11) and the block
  // extrudes in the mode in force after the G90.
  const bool block_relative_e = s.relative_xyz && !s.e_mode_set && s.e_follows_g90 ? false : s.relative_e;
  Extruder e(block_relative_e, s.at(kE), precision);
  const int zd = precision.of('Z'), fd = precision.of('F');
  if (s.relative_xyz) {
    p.emplace_back("G90");
    if (s.e_mode_set) p.push_back(e_mode);
  }

  // Retract, unless the file already did (a second retraction would be
  // pushed back by nobody). Firmware retraction when the file uses it: a
  // bare G10 while retracted is ignored by Marlin, so never two in a row.
  const bool file_fw_retracted = s.firmware_retracted;
  const bool file_e_retracted = point.pending_retraction > 1e-9;
  bool we_fw = false;
  double we_e = 0;
  if (c.retract > 0 && !file_fw_retracted && !file_e_retracted) {
    if (s.uses_firmware_retraction) {
      p.emplace_back("G10");
      we_fw = true;
    } else {
      we_e = c.retract;
      e.move(p, -we_e, c.retract_speed);
    }
  }

  // Lift above everything printed so far, never down, never past the top.
  // Heights the block makes up are rounded to the file's Z decimals; the
  // return goes to the file's own Z exactly.
  Fixed base = std::max(z0, Fixed::from_double(point.top_z));
  Fixed safe = (base + Fixed::from_double(c.lift)).rounded(zd);
  if (c.max_z > 0) safe = std::min(safe, Fixed::from_double(c.max_z).rounded(zd));
  safe = std::max(safe, z0);
  Fixed park_z = safe;
  if (c.min_park_z > 0 && Fixed::from_double(c.min_park_z) > park_z)
    park_z = Fixed::from_double(c.max_z > 0 ? std::min(c.min_park_z, c.max_z) : c.min_park_z).rounded(zd);
  park_z = std::max(park_z, safe);
  block.safe_z = safe.to_double();
  block.park_z = park_z.to_double();
  const double zf = c.z_speed * 60, xyf = c.travel_speed * 60;
  if (park_z > z0) {
    LineBuilder b;
    b.start("G1").text(" Z").text(exact_text(park_z)).word('F', zf, fd);
    p.emplace_back(b.view());
  }
  {
    LineBuilder b;
    b.start("G1")
        .text(" X")
        .text(text_of(Fixed::from_double(c.park_x), precision.of('X')))
        .text(" Y")
        .text(text_of(Fixed::from_double(c.park_y), precision.of('Y')))
        .word('F', xyf, fd);
    p.emplace_back(b.view());
  }
  if (c.wait_for_moves) p.emplace_back("M400");
  // Unload while the nozzle is still at printing temperature.
  e.move(p, -c.unload, c.unload_speed);

  std::vector<Heater> heat;
  if (c.standby) {
    heat = heaters(s, c);
    for (const Heater& h : heat)
      p.push_back(temperature_line("M104", h, heat.size() > 1 || h.tool != s.tool, 'S', c.standby_temp));
  }
  if (c.stepper_hold > 0) {
    LineBuilder b;
    b.start("M84").word('S', c.stepper_hold, 0);
    p.emplace_back(b.view());
  }
  const bool message_on_wait = c.method == PauseMethod::M0 || c.method == PauseMethod::M1;
  if (!c.message.empty() && !message_on_wait) p.push_back("M117 " + c.message);
  if (!c.host_message.empty()) p.push_back("M118 " + c.host_message);
  if (c.beep) {
    LineBuilder b;
    b.start("M300").word('S', c.beep_hz, 0).word('P', c.beep_ms, 0);
    p.emplace_back(b.view());
  }
  add_text_lines(p, c.before_wait);
  switch (c.method) {
    case PauseMethod::M0:
    case PauseMethod::M1: {
      std::string w = c.method == PauseMethod::M0 ? "M0" : "M1";
      if (!c.message.empty()) w += " " + c.message;
      p.push_back(w);
      break;
    }
    case PauseMethod::Dwell: {
      LineBuilder b;
      b.start("G4").word('S', c.dwell_seconds, 3);
      p.emplace_back(b.view());
      break;
    }
    case PauseMethod::Custom: add_text_lines(p, c.custom_wait); break;
    case PauseMethod::None: break;
    default: p.emplace_back(pause_method_name(c.method)); break;
  }

  // Resume.
  add_text_lines(r, c.after_wait);
  if (c.standby) {
    for (const Heater& h : heat) {
      bool name_tool = heat.size() > 1 || h.tool != s.tool;
      if (!c.wait_for_heat) {
        r.push_back(temperature_line("M104", h, name_tool, 'S', h.target));
      } else {
        // M109 S waits only while heating (Marlin); R waits for cooling too.
        r.push_back(temperature_line("M109", h, name_tool, c.standby_temp > h.target ? 'R' : 'S', h.target));
      }
    }
  }
  e.move(r, c.reload, c.reload_speed);
  if (c.purge > 0 || c.prime > 0) {
    // Cura's order: push back what is retracted, purge and prime, then take
    // the same retraction again so the return travel does not string and the
    // file's own unretract (or ours) finds the nozzle as it left it.
    const double in_effect = point.pending_retraction + we_e;
    const bool fw_in_effect = file_fw_retracted || we_fw;
    if (fw_in_effect) r.emplace_back("G11");
    e.move(r, in_effect, c.unretract_speed);
    e.move(r, c.purge, c.purge_speed);
    e.move(r, c.prime, c.prime_speed);
    e.move(r, -in_effect, c.retract_speed);
    if (fw_in_effect) r.emplace_back("G10");
  }
  if (park_z > safe) {
    LineBuilder b;
    b.start("G1").text(" Z").text(exact_text(safe)).word('F', zf, fd);
    r.emplace_back(b.view());
  }
  {
    LineBuilder b;
    b.start("G1").text(" X").text(exact_text(s.at(kX))).text(" Y").text(exact_text(s.at(kY))).word('F', xyf, fd);
    r.emplace_back(b.view());
  }
  if (safe != z0) {
    LineBuilder b;
    b.start("G1").text(" Z").text(exact_text(z0)).word('F', zf, fd);
    r.emplace_back(b.view());
  }
  e.move(r, we_e, c.unretract_speed);
  if (we_fw) r.emplace_back("G11");
  if (s.relative_xyz) r.emplace_back("G91");
  // Custom lines or the firmware's own pause routine may have changed it;
  // never written into a file that does not set it itself.
  if (s.e_mode_set) r.push_back(e_mode);
  // Absolute E: the file's next E word is a coordinate. Relative E after an
  // unload/purge: a later switch to M82 (Cura appends one to its end code)
  // would otherwise start from a shifted coordinate.
  if (!s.relative_e || block_relative_e != s.relative_e || e.pushed()) r.push_back("G92 E" + exact_text(s.at(kE)));
  if (s.feedrate > 0) r.push_back("G1 F" + exact_text(Fixed::from_double(s.feedrate)));
  block.net_filament = e.net();
  return block;
}

}  // namespace gcode
