#include "gcode/serial/journal/journal_point.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>

#include <fmt/format.h>

#include "gcode/core/number.hpp"

namespace gcode::serial {

namespace {

constexpr const char* kAxisKeys[4] = {"x", "y", "z", "e"};
constexpr const char* kOffsetKeys[4] = {"ox", "oy", "oz", "oe"};

std::string fixed_text(Fixed v) {
  char buf[kMaxNumberChars];
  return std::string(buf, v.format(Fixed::kDecimals, buf));
}

// The shortest text that reads back as the same double.
std::string double_text(double v) {
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, ec == std::errc() ? end : buf);
}

bool parse_double(std::string_view text, double& out) {
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size() && !text.empty();
}

// "-12.5" as an exact decimal: at most nine decimals, as Fixed holds.
bool parse_fixed(std::string_view text, Fixed& out) {
  bool negative = !text.empty() && text[0] == '-';
  if (negative) text.remove_prefix(1);
  std::size_t dot = text.find('.');
  std::string digits(text.substr(0, dot));
  int decimals = 0;
  if (dot != std::string_view::npos) {
    std::string_view frac = text.substr(dot + 1);
    digits += frac;
    decimals = static_cast<int>(frac.size());
  }
  if (digits.empty() || decimals > Fixed::kDecimals || digits.size() > 18) return false;
  std::int64_t mantissa = 0;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), mantissa);
  if (ec != std::errc() || end != digits.data() + digits.size()) return false;
  out = Fixed::from_decimal(negative ? -mantissa : mantissa, decimals);
  return true;
}

std::string_view fw_state(const MachineState& s) {
  if (s.firmware_retracted) return "out";
  return s.uses_firmware_retraction ? "in" : "";
}

std::string hotends(const MachineState& s) {
  std::size_t used = s.hotend_target.size();
  while (used > 1 && s.hotend_target[used - 1] == 0) --used;
  std::string out;
  for (std::size_t i = 0; i < used; ++i) {
    if (i > 0) out += ',';
    out += double_text(s.hotend_target[i]);
  }
  return out;
}

// Reads the fields one kind at a time; the first one that fails is named.
class FieldReader {
 public:
  FieldReader(const JournalFields& fields, std::string& problem) : fields_(fields), problem_(problem) {}

  const std::string* text(const char* key) {
    const std::string* v = fields_.find(key);
    if (v == nullptr) fail(key, "missing");
    return v;
  }
  void fixed(const char* key, Fixed& out) {
    const std::string* v = text(key);
    if (v != nullptr && !parse_fixed(*v, out)) fail(key, *v);
  }
  void number(const char* key, double& out) {
    const std::string* v = text(key);
    if (v != nullptr && !parse_double(*v, out)) fail(key, *v);
  }
  void flag(const char* key, bool& out) {
    const std::string* v = text(key);
    if (v == nullptr) return;
    if (*v != "0" && *v != "1") return fail(key, *v);
    out = *v == "1";
  }
  void list(const char* key, double* out, std::size_t size) {
    const std::string* v = text(key);
    if (v == nullptr) return;
    std::string_view rest = *v;
    for (std::size_t i = 0; i < size && !rest.empty(); ++i) {
      std::size_t comma = rest.find(',');
      if (!parse_double(rest.substr(0, comma), out[i])) return fail(key, *v);
      rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
    }
  }
  bool ok() const { return problem_.empty(); }

 private:
  void fail(const char* key, std::string_view what) {
    if (problem_.empty()) problem_ = fmt::format("field {} ({})", key, what);
  }
  const JournalFields& fields_;
  std::string& problem_;
};

// What write_machine_fields writes besides the motion fields (x y z e, f,
// fil): a field added there belongs here too.
bool same_settings(const MachineState& a, const MachineState& b) {
  return a.offset == b.offset && a.known == b.known && a.relative_xyz == b.relative_xyz &&
         a.relative_e == b.relative_e && a.inches == b.inches && a.e_mode_set == b.e_mode_set &&
         a.e_follows_g90 == b.e_follows_g90 && a.firmware_retracted == b.firmware_retracted &&
         a.uses_firmware_retraction == b.uses_firmware_retraction && a.tool == b.tool &&
         a.hotend_target == b.hotend_target && a.bed_target == b.bed_target && a.fan == b.fan &&
         a.speed_factor == b.speed_factor && a.speed_factor_backup == b.speed_factor_backup &&
         a.flow_factor == b.flow_factor && a.lifted == b.lifted && a.lift_base_z == b.lift_base_z;
}

}  // namespace

// The motion fields first (every command changes some), then the settings.
void write_machine_fields(const MachineState& s, JournalFields& f, const MachineState* before) {
  for (int a = 0; a < 4; ++a) f.set(kAxisKeys[a], fixed_text(s.at(a)));
  f.set("f", double_text(s.feedrate));
  f.set("fil", double_text(s.filament_total));
  if (before != nullptr && same_settings(*before, s)) return;
  for (int a = 0; a < 4; ++a) f.set(kOffsetKeys[a], fixed_text(s.offset[static_cast<std::size_t>(a)]));
  std::string known;
  for (int a = 0; a < 4; ++a)
    if (s.known[static_cast<std::size_t>(a)]) known += kAxisKeys[a];
  f.set("known", known);
  f.set("g91", s.relative_xyz ? "1" : "0");
  f.set("m83", s.relative_e ? "1" : "0");
  f.set("g20", s.inches ? "1" : "0");
  f.set("emode", s.e_mode_set ? "1" : "0");
  f.set("eg90", s.e_follows_g90 ? "1" : "0");
  f.set("fw", fw_state(s));
  f.set("tool", std::to_string(s.tool));
  f.set("hot", hotends(s));
  f.set("bed", double_text(s.bed_target));
  f.set("fan", double_text(s.fan));
  f.set("m220", double_text(s.speed_factor));
  f.set("m220b", double_text(s.speed_factor_backup));
  f.set("m221", double_text(s.flow_factor));
  f.set("lift", s.lifted ? "1" : "0");
  f.set("liftz", double_text(s.lift_base_z));
}

bool read_machine_fields(const JournalFields& f, MachineState& s, std::string& problem) {
  problem.clear();
  FieldReader r(f, problem);
  MachineState out;
  for (int a = 0; a < 4; ++a) {
    Fixed v;
    r.fixed(kAxisKeys[a], v);
    out.set(a, v);
    r.fixed(kOffsetKeys[a], out.offset[static_cast<std::size_t>(a)]);
  }
  if (const std::string* known = r.text("known"))
    for (int a = 0; a < 4; ++a) out.known[static_cast<std::size_t>(a)] = known->find(kAxisKeys[a]) != std::string::npos;
  r.number("f", out.feedrate);
  r.flag("g91", out.relative_xyz);
  r.flag("m83", out.relative_e);
  r.flag("g20", out.inches);
  r.flag("emode", out.e_mode_set);
  r.flag("eg90", out.e_follows_g90);
  if (const std::string* fw = r.text("fw")) {
    out.firmware_retracted = *fw == "out";
    out.uses_firmware_retraction = !fw->empty();
  }
  double tool = 0;
  r.number("tool", tool);
  out.tool = static_cast<int>(tool);
  r.number("fil", out.filament_total);
  r.list("hot", out.hotend_target.data(), out.hotend_target.size());
  r.number("bed", out.bed_target);
  r.number("fan", out.fan);
  r.number("m220", out.speed_factor);
  r.number("m220b", out.speed_factor_backup);
  r.number("m221", out.flow_factor);
  r.flag("lift", out.lifted);
  r.number("liftz", out.lift_base_z);
  if (!r.ok()) return false;
  s = out;
  return true;
}

}  // namespace gcode::serial

namespace gcode::serial {

void write_track_fields(const ResumeTrack& track, long long restore, bool drained, JournalFields& f) {
  f.set("top", double_text(track.top_z));
  f.set("retr", double_text(track.retracted));
  f.set("prime", double_text(track.retraction));
  f.set("restore", std::to_string(restore));
  f.set("drained", drained ? "1" : "0");
}

void mark_drained(JournalFields& f) { f.set("drained", "1"); }

// (A journal written before the field reads as never drained.)
bool is_drained(const JournalFields& f) { return f.get("drained") == "1"; }

ResumeTrack read_track_fields(const JournalFields& f, const MachineState& state) {
  ResumeTrack t;
  if (!parse_double(f.get("top"), t.top_z)) t.top_z = state.position[kZ];
  if (!parse_double(f.get("retr"), t.retracted)) t.retracted = 0;
  if (!parse_double(f.get("prime"), t.retraction)) t.retraction = 0;
  t.top_z = std::max(t.top_z, state.lifted ? state.lift_base_z : state.position[kZ]);
  return t;
}

}  // namespace gcode::serial
