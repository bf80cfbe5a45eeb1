#include "gcode/core/machine_state.hpp"

#include <cmath>
#include <limits>

#include "gcode/core/arc.hpp"

namespace gcode {

namespace {

constexpr char kAxisLetters[4] = {'X', 'Y', 'Z', 'E'};

// A bare G10/G11 is firmware retraction. RepRapFirmware's "G10 P0 S210" sets
// tool temperatures and "G10 L2 ..." sets work offsets: those are not.
bool is_firmware_retraction(const Line& line) {
  for (const Word& w : line)
    if (w.letter == 'P' || w.letter == 'L' || w.letter == 'R' || w.letter == 'X' || w.letter == 'Y' ||
        w.letter == 'Z')
      return false;
  return true;
}

// A word's value in millimetres as an exact decimal (inches converted).
Fixed word_mm(const Word& w, bool inches) {
  Fixed v = w.fixed();
  if (!inches) return v;
  // 25.4 = 254 / 10: exact for inch values with up to eight decimals.
  std::int64_t u = v.units();
  // (Past kMax / 254 the product below would overflow, not just saturate.)
  if (u > Fixed::kMax / 254) return Fixed::from_units(Fixed::kMax);
  if (u < -Fixed::kMax / 254) return Fixed::from_units(-Fixed::kMax);
  std::int64_t t = u * 254;
  return Fixed::from_units(t >= 0 ? (t + 5) / 10 : (t - 5) / 10);
}

// One axis of a move: its new position, exact and as a double. Forced
// inline: as a lambda GCC called it out of line four times a move (perf).
[[gnu::always_inline]] inline double axis_end(MachineState& s, int a, const Word* w, double was) {
  if (w == nullptr || !w->has_value) return was;
  auto i = static_cast<std::size_t>(a);
  const bool relative = a == kE ? s.relative_e : s.relative_xyz;
  if (!s.inches && w->plain && w->decimals <= Fixed::kDecimals) {
    if (!relative) {
      // The common case: an absolute plain decimal in mm. Its double is the
      // word's own value, no division by 10^9 needed.
      s.exact[i] = w->fixed();
      s.known[i] = true;
      return w->value();
    }
    // Relative E as most slicers write it: no call to convert units.
    s.exact[i] += w->fixed();
    return s.exact[i].to_double();
  }
  Fixed v = word_mm(*w, s.inches);
  if (relative) {
    s.exact[i] += v;
  } else {
    s.exact[i] = v;
    s.known[i] = true;
  }
  return s.exact[i].to_double();
}

// The filament of a move, from its exact difference `d`. A plain relative
// E word in mm is that difference (unless the sum saturated), and where
// both are exact integers as doubles (below 2^53 units) the word's own
// value is the same correctly rounded double as d.to_double(): one
// division by 10^9 less on most extrusions (perf: the hottest instruction
// of a whole pass). A zero keeps to_double()'s sign.
double filament_of(const MachineState& s, const Word& e, Fixed d) {
  constexpr std::int64_t kExactInDouble = std::int64_t{1} << 53;
  if (s.relative_e && !s.inches && e.plain && e.decimals <= Fixed::kDecimals && d.units() != 0 &&
      d.units() < kExactInDouble && d.units() > -kExactInDouble && d == e.fixed())
    return e.value();
  return d.to_double();
}

void apply_motion(MachineState& s, const Line& line, Move& m) {
  const bool inches = s.inches;
  // One pass over the words instead of a find() per letter (this runs for
  // most lines of a file); the first word of a letter counts, as with find().
  const Word* axis[4] = {};
  const Word* f = nullptr;
  for (const Word& w : line) {
    switch (w.letter) {
      case 'X': if (axis[kX] == nullptr) axis[kX] = &w; break;
      case 'Y': if (axis[kY] == nullptr) axis[kY] = &w; break;
      case 'Z': if (axis[kZ] == nullptr) axis[kZ] = &w; break;
      case 'E': if (axis[kE] == nullptr) axis[kE] = &w; break;
      case 'F': if (f == nullptr) f = &w; break;
      default: break;
    }
  }
  if (f != nullptr && f->has_value) {
    double v = f->value();
    if (v > 0) s.feedrate = inches ? v * kMmPerInch : v;
  }
  // The new position is worked out in scalars and only then stored: reading
  // s.position back as a whole right after storing single axes defeats the
  // CPU's store forwarding, which cost more than the rest of this function.
  const double start[4] = {s.position[kX], s.position[kY], s.position[kZ], s.position[kE]};
  const Fixed e0 = s.exact[kE];
  // Each axis in a scalar of its own (inlined with a constant axis): an
  // array indexed in a loop was stored 8 bytes at a time and then copied 16
  // at a time, a store-forwarding stall on every move.
  const double end[4] = {axis_end(s, kX, axis[kX], start[kX]), axis_end(s, kY, axis[kY], start[kY]),
                         axis_end(s, kZ, axis[kZ], start[kZ]), axis_end(s, kE, axis[kE], start[kE])};
  s.position = Vec4{{end[kX], end[kY], end[kZ], end[kE]}};
  m.end = s.position;
  m.feedrate = s.feedrate;
  // The exact difference: 5.0348 after 4.9 is 0.1348, not 0.13480000000000025.
  m.filament = axis[kE] != nullptr ? filament_of(s, *axis[kE], s.exact[kE] - e0) : 0.0;
  double dx = end[kX] - start[kX], dy = end[kY] - start[kY], dz = end[kZ] - start[kZ];
  m.z_changed = dz != 0;
  if (m.kind == MoveKind::Arc) {
    Arc arc = make_arc(line, start[kX], start[kY], end[kX], end[kY], inches ? kMmPerInch : 1.0);
    m.is_arc_clockwise = line.number == 2;
    if (arc.valid) {
      m.xy_length = arc.length_xy();
      m.length = std::hypot(m.xy_length, dz);
      return;
    }
  }
  // sqrt is several times cheaper than hypot, which only matters for values
  // beyond 1e150 (junk input): those take the careful path.
  m.xy_length = std::sqrt(dx * dx + dy * dy);
  m.length = dz == 0 ? m.xy_length : std::sqrt(dx * dx + dy * dy + dz * dz);
  if (!std::isfinite(m.length)) {
    m.xy_length = std::hypot(dx, dy);
    m.length = std::hypot(m.xy_length, dz);
  }
}

void apply_set_position(MachineState& s, const Line& line) {
  for (int a = 0; a < 4; ++a) {
    const Word* w = line.find(kAxisLetters[a]);
    if (w == nullptr || !w->has_value) continue;
    auto i = static_cast<std::size_t>(a);
    Fixed machine = s.exact[i] + s.offset[i];
    s.set(a, word_mm(*w, s.inches));
    s.offset[i] = machine - s.exact[i];
    s.known[i] = true;
  }
}

void apply_home(MachineState& s, const Line& line) {
  bool any = line.has('X') || line.has('Y') || line.has('Z');
  for (int a = 0; a < 3; ++a) {
    if (any && !line.has(kAxisLetters[a])) continue;
    s.set(a, Fixed());
    s.offset[static_cast<std::size_t>(a)] = Fixed();
    s.known[static_cast<std::size_t>(a)] = true;
  }
}

void apply_heater_fan(MachineState& s, const Line& line) {
  HeaterFanLine h;
  if (!read_heater_fan(line, s.tool, h)) return;
  const double v = h.value.to_double();
  switch (h.kind) {
    case HeaterFanLine::Kind::Hotend:
      if (h.index >= 0 && h.index < static_cast<int>(s.hotend_target.size()))
        s.hotend_target[static_cast<std::size_t>(h.index)] = v;
      break;
    case HeaterFanLine::Kind::Bed: s.bed_target = v; break;
    case HeaterFanLine::Kind::Fan:
      if (h.index == 0) s.fan = v;
      break;
    case HeaterFanLine::Kind::Chamber: break;
  }
}

void apply_speed_factor(MachineState& s, const Line& line) {
  if (line.has('B')) s.speed_factor_backup = s.speed_factor;
  const Word* f = line.find('S');
  if (f != nullptr && f->has_value) s.speed_factor = f->value();
  if (line.has('R')) s.speed_factor = s.speed_factor_backup;
}

void apply_m(MachineState& s, const Line& line) {
  switch (line.number) {
    case 82: case 83:
      s.relative_e = line.number == 83;
      s.e_mode_set = true;
      s.e_follows_g90 = true;
      break;
    case 104: case 109: case 140: case 190: case 106: case 107: case 568: apply_heater_fan(s, line); break;
    case 220: apply_speed_factor(s, line); break;
    case 221: {
      const Word* f = line.find('S');
      if (f != nullptr && f->has_value && !line.has('T')) s.flow_factor = f->value();
      break;
    }
    default: break;
  }
}

void track_lift(MachineState& s, Move& m) {
  if (m.extruding) {
    s.lifted = false;
    return;
  }
  double z0 = m.start[kZ], z1 = m.end[kZ];
  if (!s.lifted && z1 > z0) {
    s.lifted = true;
    s.lift_base_z = z0;
    m.z_lift = true;
  } else if (s.lifted && z1 < z0 && z1 <= s.lift_base_z + 1e-6) {
    s.lifted = false;
    m.z_hop_return = true;
  }
}

}  // namespace

Move MachineState::apply(const Line& line) {
  Move m(position, feedrate);
  if (line.kind != CommandKind::Standard) return m;
  if (line.letter == 'T') {
    tool = line.number;
    return m;
  }
  if (line.letter == 'M') {
    apply_m(*this, line);
    return m;
  }
  if (line.letter != 'G' || line.subcode >= 0) return m;
  switch (line.number) {
    case 0: case 1: case 2: case 3: {
      m.kind = line.number <= 1 ? MoveKind::Linear : MoveKind::Arc;
      if (line.malformed) {
        // Never guess: a move we cannot read is left out of the state.
        m.ignored = true;
        return m;
      }
      apply_motion(*this, line, m);
      filament_total += m.filament;
      m.extruding = m.filament > 0 && m.xy_length + std::fabs(m.end[kZ] - m.start[kZ]) > 0;
      m.travel = m.filament <= 0 && m.length > 0;
      track_lift(*this, m);
      return m;
    }
    case 10: case 11:
      if (!is_firmware_retraction(line)) {
        if (line.number == 10) apply_heater_fan(*this, line);  // RepRapFirmware: G10 P<tool> S<temperature>
        return m;
      }
      uses_firmware_retraction = true;
      firmware_retracted = line.number == 10;
      m.kind = line.number == 10 ? MoveKind::FirmwareRetract : MoveKind::FirmwareUnretract;
      return m;
    case 20: inches = true; return m;
    case 21: inches = false; return m;
    case 28:
      lifted = false;
      apply_home(*this, line);
      m.kind = MoveKind::Home;
      m.end = position;
      return m;
    case 90: case 91:
      relative_xyz = line.number == 91;
      if (e_follows_g90) {
        // Marlin: G90/G91 set the E mode as well; the file has said it.
        relative_e = relative_xyz;
        e_mode_set = true;
      }
      return m;
    case 92:
      if (line.has('Z')) lifted = false;
      apply_set_position(*this, line);
      m.kind = MoveKind::SetPosition;
      m.end = position;
      return m;
    default:
      return m;
  }
}

}  // namespace gcode

namespace gcode {

bool same_machine(const MachineState& a, const MachineState& b) {
  return a.exact == b.exact && a.offset == b.offset && a.known == b.known && a.feedrate == b.feedrate &&
         a.relative_xyz == b.relative_xyz && a.relative_e == b.relative_e && a.e_mode_set == b.e_mode_set &&
         a.e_follows_g90 == b.e_follows_g90 && a.inches == b.inches &&
         a.firmware_retracted == b.firmware_retracted && a.uses_firmware_retraction == b.uses_firmware_retraction &&
         a.tool == b.tool && a.hotend_target == b.hotend_target && a.bed_target == b.bed_target && a.fan == b.fan &&
         a.speed_factor == b.speed_factor && a.flow_factor == b.flow_factor &&
         a.speed_factor_backup == b.speed_factor_backup &&
         a.lifted == b.lifted && a.lift_base_z == b.lift_base_z;
}

namespace {

// The value of a word that has one, as an exact decimal.
bool word_fixed(const Line& line, char letter, Fixed& out) {
  const Word* w = line.find(letter);
  if (w == nullptr || !w->has_value) return false;
  out = w->fixed();
  return true;
}

// (A value past int's range, "T66666...", is clamped: converting it as it
// is would be undefined.)
int word_int(const Line& line, char letter, int fallback) {
  const double v = line.value_or(letter, fallback);
  if (!(v > std::numeric_limits<int>::min())) return std::numeric_limits<int>::min();
  if (!(v < std::numeric_limits<int>::max())) return std::numeric_limits<int>::max();
  return static_cast<int>(v);
}

// A heater's target: S, or R ("wait while heating or cooling").
bool target(const Line& line, Fixed& out) { return word_fixed(line, 'S', out) || word_fixed(line, 'R', out); }

}  // namespace

bool read_heater_fan(const Line& line, int tool, HeaterFanLine& out) {
  using Kind = HeaterFanLine::Kind;
  if (line.kind != CommandKind::Standard) return false;
  if (line.letter == 'G') {  // RepRapFirmware: G10 P<tool> S<active> R<standby>
    if (line.number != 10 || !line.has('P') || !word_fixed(line, 'S', out.value)) return false;
    out.kind = Kind::Hotend;
    out.index = word_int(line, 'P', tool);
    return true;
  }
  if (line.letter != 'M') return false;
  switch (line.number) {
    case 104: case 109:
      out.kind = Kind::Hotend;
      out.index = word_int(line, 'T', tool);
      return target(line, out.value);
    case 568:
      out.kind = Kind::Hotend;
      out.index = word_int(line, 'P', tool);
      return word_fixed(line, 'S', out.value);
    case 140: case 190:
      out.kind = Kind::Bed;
      out.index = 0;
      return target(line, out.value);
    case 141: case 191:
      out.kind = Kind::Chamber;
      out.index = 0;
      return target(line, out.value);
    case 106:
      if (!word_fixed(line, 'S', out.value)) out.value = Fixed::from_int(255);
      out.kind = Kind::Fan;
      out.index = word_int(line, 'P', 0);
      return true;
    case 107:
      out.value = Fixed();
      out.kind = Kind::Fan;
      out.index = word_int(line, 'P', 0);
      return true;
    default:
      return false;
  }
}

}  // namespace gcode
