// The independent checker of gc-subdivide (subdivide_check.hpp), compiled
// once into the test kit, at the kit's optimisation (the sanitizer tree
// builds the test files themselves at -O0).
#include "subdivide_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/arc.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/machine_state.hpp"
#include "test_support.hpp"

namespace gctest {
namespace detail {

std::string_view without_ending(std::string_view l) {
  while (!l.empty() && (l.back() == '\n' || l.back() == '\r')) l.remove_suffix(1);
  return l;
}

double distance_to_segment(const gcode::Vec4& p, const gcode::Vec4& a, const gcode::Vec4& b) {
  double d[3], q[3], len2 = 0, t = 0;
  for (int i = 0; i < 3; ++i) {
    d[i] = b[i] - a[i];
    q[i] = p[i] - a[i];
    len2 += d[i] * d[i];
    t += q[i] * d[i];
  }
  t = len2 > 0 ? std::clamp(t / len2, 0.0, 1.0) : 0.0;
  double s = 0;
  for (int i = 0; i < 3; ++i) s += (q[i] - t * d[i]) * (q[i] - t * d[i]);
  return std::sqrt(s);
}

bool same_position(const gcode::MachineState& a, const gcode::MachineState& b, double tol) {
  for (int i = 0; i < 4; ++i)
    if (std::fabs(a.position[i] - b.position[i]) > tol || std::fabs((a.offset[static_cast<std::size_t>(i)] - b.offset[static_cast<std::size_t>(i)]).to_double()) > tol)
      return false;
  return true;
}

bool same_modes(const gcode::MachineState& a, const gcode::MachineState& b) {
  return a.feedrate == b.feedrate && a.relative_xyz == b.relative_xyz && a.relative_e == b.relative_e &&
         a.inches == b.inches && a.tool == b.tool;
}

// Whether the tool must have split this input move under `limits`.
bool must_split(const gcode::Line& l, const gcode::Move& m, const SubdivideLimits& limits) {
  if (l.has_line_number || l.has_checksum) return false;
  for (const gcode::Word& w : l)
    if (!w.has_value || std::string_view("XYZEFIJR").find(w.letter) == std::string_view::npos) return false;
  if (m.kind == gcode::MoveKind::Arc) return limits.arcs;
  if (m.xy_length <= 0 || (m.travel && !limits.travel)) return false;
  double limit = limits.limit(m.feedrate);
  return limit > 0 && m.length > limit + 1e-9;
}

}  // namespace detail

SubdivideCheck check_subdivision(std::string_view input, std::string_view output, const SubdivideLimits& limits) {
  using namespace gcode;
  SubdivideCheck r;
  std::vector<std::string> in = split_lines(input), out = split_lines(output);
  MachineState is = initial_state(input), os = is;
  std::size_t j = 0;
  auto fail = [&](std::size_t i, const std::string& what) {
    r.failures.push_back("input line " + std::to_string(i + 1) + ": " + what + ": " +
                         std::string(detail::without_ending(in[i])));
  };
  for (std::size_t i = 0; i < in.size() && r.failures.size() < 5; ++i) {
    Line il = Line::parse(detail::without_ending(in[i]));
    MachineState before = is;
    Move im = is.apply(il);
    bool selected = limits.selected.empty() || limits.selected[i];
    bool motion = (im.kind == MoveKind::Linear || im.kind == MoveKind::Arc) && !im.ignored && !il.malformed;
    if (j < out.size() && out[j] == in[i]) {  // (e) and unsplit moves
      os.apply(Line::parse(detail::without_ending(out[j++])));
      if (motion && selected && detail::must_split(il, im, limits)) fail(i, "left whole although over the limit");
    } else if (!motion || !selected) {
      fail(i, "not copied byte for byte");
      break;
    } else {
      ++r.moves_split;
      bool arc = im.kind == MoveKind::Arc;
      if (arc) ++r.arcs;
      double scale = before.inches ? 25.4 : 1.0;
      Arc geometry;
      if (arc)
        geometry = make_arc(il, im.start[kX], im.start[kY], im.end[kX], im.end[kY], scale);
      double filament = 0;
      std::size_t count = 0;
      for (;;) {
        if (j >= out.size()) {
          fail(i, "output ends inside the pieces of this move");
          break;
        }
        Line ol = Line::parse(detail::without_ending(out[j++]));
        if (!ol.is_g(arc ? 1 : il.number) || ol.malformed) {
          fail(i, "a piece is not a G" + std::to_string(arc ? 1 : il.number) + " move: " + out[j - 1]);
          break;
        }
        Move om = os.apply(ol);
        ++count;
        filament += om.filament;
        double off = 0;  // (a)
        if (arc) {
          off = std::fabs(std::hypot(om.end[kX] - geometry.cx, om.end[kY] - geometry.cy) - geometry.radius);
        } else {
          off = detail::distance_to_segment(om.end, im.start, im.end);
        }
        if (off > 0.001) fail(i, "a piece ends " + std::to_string(off) + " mm off the move");
        double limit = limits.limit(om.feedrate);  // (d)
        if (limit > 0 && om.length > limit + 1e-9 && (limits.travel || !im.travel))
          fail(i, "a piece of " + std::to_string(om.length) + " mm is over the limit " + std::to_string(limit));
        bool at_end = detail::same_position(os, is, 1e-7);
        if (!at_end && !arc && om.length < limits.min - 0.002)
          fail(i, "a piece of " + std::to_string(om.length) + " mm is under the minimum");
        if (at_end || count > 10000000) break;
      }
      r.pieces += count;
      if (std::fabs(filament - im.filament) > 1e-5)  // (b)
        fail(i, "pieces push " + std::to_string(filament) + " mm of filament, the move " + std::to_string(im.filament));
    }
    if (!detail::same_position(os, is, 1e-7) || !detail::same_modes(os, is))  // (c)
      fail(i, "state differs after this line");
  }
  if (r.failures.empty() && j != out.size()) r.failures.push_back("output has extra lines: " + out[j]);
  return r;
}

}  // namespace gctest
