#pragma once
// The independent checker for gc-speedup and the speed stage: replays the
// input and the output through MachineState side by side and proves, line by
// line:
//   (a) the same lines in the same order: every line that is not a move is
//       byte-identical; a move line differs at most in its F word and a marker
//       comment appended after its own comment;
//   (b) the same machine after every line (positions, E, G92 offsets, modes,
//       tool), feed rate aside;
//   (c) every move the rule changes (extruding moves in the region; travel in
//       XY with --travel) runs at exactly its original effective F times the
//       factor (or at --speed), rounded half away from zero to the decimals
//       of the F the output wrote, never more decimals than the input uses;
//       unless a cap applies, and then it is within the cap, on the same side
//       of its original speed, and as close to the cap as the decimals allow;
//   (d) every other move runs at exactly its original effective F;
//   (e) every changed extruding move's flow (filament per mm x area x speed)
//       is within --max-flow.
// It knows the rule only from the documented behaviour, not from the library.
#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/fixed.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/machine_state.hpp"
#include "test_support.hpp"

namespace gctest {

struct SpeedRule {
  // Per input line (0-based): the factor in force there; 0 = outside the region.
  std::vector<double> factor;
  double speed = 0;          // --speed (mm/s) instead of the factor
  bool travel = false;       // --travel
  double travel_factor = 0;  // --travel-factor
  double max_speed = 0, min_speed = 0, max_flow = 0;
  double filament = 1.75;
  std::string mark = "gc-speedup";
  // Extra room around the exact product (a ramp's factors between its ends
  // are not short decimals).
  double slack = 0;
};

struct SpeedCheck {
  std::size_t moves = 0;          // motion lines
  std::size_t changed = 0;        // moves at a new speed
  std::size_t capped = 0;         // changed moves a cap held back (or kept at their speed)
  std::size_t inherited_in = 0;   // changed moves without an F word that follow an unchanged move
  std::size_t inherited_out = 0;  // unchanged moves without an F word that follow a changed move
  std::size_t marked = 0;         // lines with a marker comment
  std::vector<std::string> failures;
  std::string first_failure() const { return failures.empty() ? std::string() : failures.front(); }
};

namespace speed_detail {

inline std::string_view strip_ending(std::string_view l) {
  while (!l.empty() && (l.back() == '\n' || l.back() == '\r')) l.remove_suffix(1);
  return l;
}

// The words of a line but F, as written.
inline std::string words_but_f(const gcode::Line& l) {
  std::string s(l.command);
  for (const gcode::Word& w : l)
    if (w.letter != 'F') s += std::string(" ") + w.letter + std::string(w.raw);
  return s;
}

inline gcode::Fixed times(gcode::Fixed a, gcode::Fixed b) {
  __extension__ using Wide = __int128;
  Wide p = static_cast<Wide>(a.units()) * b.units();
  Wide q = p / gcode::Fixed::kOne, r = p % gcode::Fixed::kOne;
  if (2 * (r < 0 ? -r : r) >= gcode::Fixed::kOne) q += p < 0 ? -1 : 1;
  return gcode::Fixed::from_units(static_cast<std::int64_t>(q));
}

inline bool same_but_feed(const gcode::MachineState& a, const gcode::MachineState& b) {
  return a.exact == b.exact && a.offset == b.offset && a.known == b.known && a.relative_xyz == b.relative_xyz &&
         a.relative_e == b.relative_e && a.inches == b.inches && a.tool == b.tool &&
         a.firmware_retracted == b.firmware_retracted;
}

}  // namespace speed_detail

inline SpeedCheck check_speed(std::string_view input, std::string_view output, const SpeedRule& rule) {
  using gcode::Fixed;
  namespace d = speed_detail;
  SpeedCheck c;
  auto fail = [&c](std::size_t i, const std::string& what) {
    if (c.failures.size() < 20) c.failures.push_back("line " + std::to_string(i + 1) + ": " + what);
  };
  std::vector<std::string> in = split_lines(input), out = split_lines(output);
  if (in.size() != out.size()) {
    c.failures.push_back("line count " + std::to_string(in.size()) + " in, " + std::to_string(out.size()) + " out");
    return c;
  }
  const double kPi = 3.141592653589793;
  const double area = kPi / 4 * rule.filament * rule.filament;
  const std::string marker = " ; " + rule.mark;
  gcode::MachineState si = initial_state(input), so = si;
  int input_decimals = 0;  // the most F decimals the input uses
  for (const std::string& l : in) {
    gcode::Line line = gcode::Line::parse(d::strip_ending(l));
    if (const gcode::Word* f = line.find('F'); f != nullptr && f->has_value)
      input_decimals = std::max<int>(input_decimals, f->decimals);
  }
  int out_decimals = 0;    // decimals of the F word the output's speed comes from
  bool previous_changed = false;
  for (std::size_t i = 0; i < in.size(); ++i) {
    std::string_view ti = d::strip_ending(in[i]), to = d::strip_ending(out[i]);
    gcode::Line li = gcode::Line::parse(ti), lout = gcode::Line::parse(to);
    gcode::Move mi = si.apply(li), mo = so.apply(lout);
    if (const gcode::Word* f = lout.find('F'); f != nullptr && f->has_value && mo.kind != gcode::MoveKind::None) {
      out_decimals = f->decimals;
      if (f->decimals > input_decimals && out[i] != in[i])
        fail(i, "F written with more decimals than the input uses: " + std::string(to));
    }
    if (!d::same_but_feed(si, so)) fail(i, "the machine differs after the line: " + std::string(to));
    if (to.find(marker) != std::string_view::npos) ++c.marked;
    bool move = (mi.kind == gcode::MoveKind::Linear || mi.kind == gcode::MoveKind::Arc) && !mi.ignored;
    if (!move) {
      if (out[i] != in[i]) fail(i, "not a move, yet changed: '" + std::string(ti) + "' -> '" + std::string(to) + "'");
      continue;
    }
    ++c.moves;
    if (out[i] != in[i]) {
      std::size_t at = to.find(marker);
      std::string_view base = at == std::string_view::npos ? to : to.substr(0, at);
      gcode::Line lb = gcode::Line::parse(base);
      if (at == std::string_view::npos) fail(i, "edited without a marker: " + std::string(to));
      if (d::words_but_f(lb) != d::words_but_f(li) || lb.comment != li.comment)
        fail(i, "more than F changed: '" + std::string(ti) + "' -> '" + std::string(to) + "'");
      if (in[i].substr(ti.size()) != out[i].substr(to.size())) fail(i, "line ending changed");
    }
    const double fi = mi.feedrate, fo = mo.feedrate;
    double k = i < rule.factor.size() ? rule.factor[i] : 0;
    bool eligible = mi.extruding || ((rule.travel || rule.travel_factor > 0) && mi.travel && mi.filament == 0 &&
                                     !mi.z_changed && mi.xy_length > 0);
    bool has_f = li.find('F') != nullptr;
    if (!(k > 0 && eligible && fi > 0)) {
      if (fo != fi) fail(i, "outside the change, F " + std::to_string(fo) + " instead of " + std::to_string(fi));
      if (previous_changed && !has_f) ++c.inherited_out;
      previous_changed = false;
      continue;
    }
    if (mi.travel && rule.travel_factor > 0) k = rule.travel_factor;
    Fixed exact = rule.speed > 0 && !(mi.travel && rule.travel_factor > 0)
                      ? Fixed::from_double(rule.speed * 60)
                      : d::times(Fixed::from_double(fi), Fixed::from_double(k));
    double x = exact.to_double();
    double hi = rule.max_speed > 0 ? rule.max_speed * 60 : HUGE_VAL;
    if (rule.max_flow > 0 && mi.extruding) hi = std::min(hi, rule.max_flow * 60 / (mi.filament / mi.length * area));
    double lo = rule.min_speed > 0 ? rule.min_speed * 60 : 0;
    double unit = std::pow(10.0, -out_decimals);
    if (x >= lo && x <= hi) {
      Fixed want = exact.rounded(out_decimals);
      bool ok = rule.slack > 0 ? std::fabs(fo - x) <= unit / 2 + rule.slack : Fixed::from_double(fo) == want;
      if (!ok) fail(i, "F " + std::to_string(fo) + ", expected " + std::to_string(x) + " rounded: " + std::string(to));
    } else {
      ++c.capped;
      bool up = x > fi;
      if (fo > hi * (1 + 1e-12) && fo != fi) fail(i, "above the cap: F " + std::to_string(fo) + " > " + std::to_string(hi));
      if (fo < lo * (1 - 1e-12) && fo != fi) fail(i, "below the cap: F " + std::to_string(fo) + " < " + std::to_string(lo));
      if (up ? fo < fi : fo > fi) fail(i, "a cap turned the change around: F " + std::to_string(fi) + " -> " + std::to_string(fo));
      bool at_cap = (x > hi && fo >= hi - unit - 1e-9) || (x < lo && fo <= lo + unit + 1e-9);
      if (fo != fi && !at_cap) fail(i, "capped short of the cap: F " + std::to_string(fo));
    }
    if (fo != fi) {
      ++c.changed;
      if (!previous_changed && !has_f) ++c.inherited_in;
    }
    if (rule.max_flow > 0 && mi.extruding && fo != fi && mi.filament / mi.length * area * fo / 60 > rule.max_flow * (1 + 1e-12))
      fail(i, "flow above --max-flow: F " + std::to_string(fo));
    previous_changed = fo != fi;
  }
  return c;
}

}  // namespace gctest
