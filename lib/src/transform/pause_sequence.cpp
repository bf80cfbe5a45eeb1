#include "gcode/transform/pause_sequence.hpp"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "gcode/core/line_builder.hpp"
#include "gcode/core/number.hpp"

namespace gcode {

namespace {

// The shortest text, from `decimals` up, that reads back as exactly `value`:
// the resume must land on the very coordinate the file is at, not one
// rounded to the slicer's decimals (for a value parsed from the file the
// slicer's decimals are already exact).
std::string exact_number(double value, int decimals) {
  char buffer[kMaxNumberChars];
  for (int d = decimals; d <= 9; ++d) {
    std::size_t n = format_number(value, d, buffer);
    double back = 0;
    if (parse_number(std::string_view(buffer, n), back) && back == value) return std::string(buffer, n);
  }
  // A sum of relative moves (0.1 + 0.2) needs all its digits: the shortest
  // fixed notation that reads back exactly (never an exponent).
  char wide[400];
  auto res = std::to_chars(wide, wide + sizeof wide, value, std::chars_format::fixed);
  if (res.ec == std::errc()) return std::string(wide, res.ptr);
  return std::string(buffer, format_number(value, 9, buffer));
}

double parsed(const std::string& text) {
  double v = 0;
  parse_number(text, v);
  return v;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::toupper(static_cast<unsigned char>(a[i])) != std::toupper(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

void add_text_lines(std::vector<std::string>& out, std::string_view text) {
  while (!text.empty()) {
    std::size_t nl = text.find('\n');
    std::string_view one = text.substr(0, nl);
    if (!one.empty() && one.back() == '\r') one.remove_suffix(1);
    if (!one.empty()) out.emplace_back(one);
    if (nl == std::string_view::npos) break;
    text.remove_prefix(nl + 1);
  }
}

// Writes the E moves of a block in the file's own E mode, keeping the E
// coordinate the firmware will hold (the value each written text reads as).
class Extruder {
 public:
  Extruder(bool relative, double start) : relative_(relative), e_(start) {}

  void move(std::vector<std::string>& out, double amount, double speed_mm_s) {
    if (amount == 0) return;
    // Chunks keep each E move under the firmware's lengthy-extrude guard;
    // whole 150 mm pieces then the rest, so every piece is a short decimal.
    double left = amount;
    while (left != 0) {
      double piece = std::fabs(left) > kMaxExtrudeChunk ? std::copysign(kMaxExtrudeChunk, left) : left;
      left = std::fabs(left) > kMaxExtrudeChunk ? left - piece : 0;
      LineBuilder b;
      b.start("G1");
      if (relative_) {
        std::string t = exact_number(piece, 5);
        b.text(" E").text(t);
        net_ += parsed(t);
      } else {
        std::string t = exact_number(e_ + piece, 5);
        double next = parsed(t);
        net_ += next - e_;
        e_ = next;
        b.text(" E").text(t);
      }
      b.word('F', speed_mm_s * 60, 2);
      out.emplace_back(b.view());
    }
  }
  double net() const { return net_; }

 private:
  bool relative_;
  double e_;
  double net_ = 0;
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
  b.word(letter, t, 2);
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
  const double x0 = s.position[kX], y0 = s.position[kY], z0 = s.position[kZ];
  const std::string e_mode = s.relative_e ? "M83" : "M82";
  Extruder e(s.relative_e, s.position[kE]);

  // The block moves in absolute XYZ. On Marlin G90 also makes E absolute, so
  // the file's E mode is set again right after it.
  if (s.relative_xyz) {
    p.emplace_back("G90");
    p.push_back(e_mode);
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
  double base = std::max(z0, point.top_z);
  double safe = base + c.lift;
  if (c.max_z > 0) safe = std::min(safe, c.max_z);
  safe = std::max(safe, z0);
  double park_z = safe;
  if (c.min_park_z > park_z) park_z = c.max_z > 0 ? std::min(c.min_park_z, c.max_z) : c.min_park_z;
  park_z = std::max(park_z, safe);
  block.safe_z = safe;
  block.park_z = park_z;
  const double zf = c.z_speed * 60, xyf = c.travel_speed * 60;
  if (park_z > z0) {
    LineBuilder b;
    b.start("G1").text(" Z").text(exact_number(park_z, 3)).word('F', zf, 2);
    p.emplace_back(b.view());
  }
  {
    LineBuilder b;
    b.start("G1").text(" X").text(exact_number(c.park_x, 3)).text(" Y").text(exact_number(c.park_y, 3)).word('F', xyf, 2);
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
    b.start("G1").text(" Z").text(exact_number(safe, 3)).word('F', zf, 2);
    r.emplace_back(b.view());
  }
  {
    LineBuilder b;
    b.start("G1").text(" X").text(exact_number(x0, 3)).text(" Y").text(exact_number(y0, 3)).word('F', xyf, 2);
    r.emplace_back(b.view());
  }
  if (safe != z0) {
    LineBuilder b;
    b.start("G1").text(" Z").text(exact_number(z0, 3)).word('F', zf, 2);
    r.emplace_back(b.view());
  }
  e.move(r, we_e, c.unretract_speed);
  if (we_fw) r.emplace_back("G11");
  if (s.relative_xyz) r.emplace_back("G91");
  // Always: custom lines or the firmware's own pause routine may have changed it.
  r.push_back(e_mode);
  // Absolute E: the file's next E word is a coordinate. Relative E after an
  // unload/purge: a later switch to M82 (Cura appends one to its end code)
  // would otherwise start from a shifted coordinate.
  if (!s.relative_e || e.net() != 0) r.push_back("G92 E" + exact_number(s.position[kE], 5));
  if (s.feedrate > 0) r.push_back("G1 F" + exact_number(s.feedrate, 0));
  block.net_filament = e.net();
  return block;
}

}  // namespace gcode
