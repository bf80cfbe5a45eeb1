#include "gcode/objects/catch_up.hpp"

#include <cmath>

#include "gcode/transform/stream_tracker.hpp"
#include "gcode/transform/transition.hpp"

namespace gcode {

namespace {

bool line_sets(const Line& line, char axis) {
  const Word* w = line.find(axis);
  return w != nullptr && w->has_value;
}

}  // namespace

void StreamCatchUp::leave(const MachineState& printed, double retracted) {
  if (behind_) return;
  behind_ = true;
  printer_ = printed;
  retracted_ = retracted;
}

void StreamCatchUp::before(const TrackedLine& t, double in_retracted, std::vector<std::string>& out) {
  if (!behind_ || !is_motion_line(t.move)) return;
  const MachineState& in = t.before;
  const Line& line = t.line;
  const int ed = precision_.of('E');
  Transition tr(printer_, precision_, out,
                {.z_feed = moves_.z_feed, .xy_feed = moves_.xy_feed, .e_feed = moves_.e_feed, .g0 = true});
  if (tr.printer().firmware_retracted != in.firmware_retracted) tr.firmware_retraction(in.firmware_retracted);
  // Retraction: deeper at once (the input travels retracted here); primed
  // only before an extrusion (no ooze over what was left out).
  const Fixed in_depth = Fixed::from_double(in_retracted).rounded(ed);
  auto depth_to_input = [&](bool prime) {
    const Fixed now = Fixed::from_double(retracted_).rounded(ed);
    if (now == in_depth || (now > in_depth && !prime)) return;
    tr.extrude(now - in_depth, moves_.e_feed);
    retracted_ = in_retracted;
  };
  depth_to_input(t.move.extruding);
  const bool in_xy = (line_sets(line, 'X') || line_sets(line, 'Y')) && t.move.kind != MoveKind::FirmwareRetract &&
                     t.move.kind != MoveKind::FirmwareUnretract;
  const bool needs_xy = t.move.extruding || t.move.kind == MoveKind::Arc || in.relative_xyz ||
                        (in_xy && !(line_sets(line, 'X') && line_sets(line, 'Y')));
  const bool needs_z = t.move.extruding || t.move.kind == MoveKind::Arc || (in.relative_xyz && line_sets(line, 'Z')) ||
                       (in_xy && !line_sets(line, 'Z'));
  const Fixed z = in.at(kZ);
  const bool xy_off = tr.printer().at(kX) != in.at(kX) || tr.printer().at(kY) != in.at(kY);
  if (needs_z && needs_xy && xy_off && z > tr.printer().at(kZ)) tr.move_z(z);
  if (needs_xy && xy_off && in.known[kX] && in.known[kY]) tr.move_xy(in.at(kX), in.at(kY));
  if (needs_z && in.known[kZ] && tr.printer().at(kZ) != z) tr.move_z(z);
  // The E coordinate where the line's E is absolute.
  if (!in.relative_e && (line_sets(line, 'E') || t.move.extruding)) tr.e_coordinate(in.at(kE));
  if (!line_sets(line, 'F')) tr.feed_rate(in.feedrate);
  printer_ = tr.printer();
}

void StreamCatchUp::passed(const TrackedLine& t, double in_retracted) {
  if (!behind_) return;
  const Move m = printer_.apply(t.line);
  retracted_ = RetractionTracker::after(retracted_, m);
  check_caught_up(t.state, in_retracted);
}

void StreamCatchUp::check_caught_up(const MachineState& in, double in_retracted) {
  const MachineState& p = printer_;
  const int ed = precision_.of('E');
  const bool same = p.at(kX) == in.at(kX) && p.at(kY) == in.at(kY) && p.at(kZ) == in.at(kZ) &&
                    (in.relative_e || p.at(kE) == in.at(kE)) && p.feedrate == in.feedrate &&
                    p.firmware_retracted == in.firmware_retracted && p.relative_e == in.relative_e &&
                    p.relative_xyz == in.relative_xyz &&
                    Fixed::from_double(retracted_).rounded(ed) == Fixed::from_double(in_retracted).rounded(ed);
  if (same) behind_ = false;
}

void StreamCatchUp::all(const MachineState& target, double in_retracted, std::vector<std::string>& out) {
  if (!behind_) return;
  Transition tr(printer_, precision_, out,
                {.z_feed = moves_.z_feed, .xy_feed = moves_.xy_feed, .e_feed = moves_.e_feed, .g0 = true});
  const int ed = precision_.of('E');
  if (tr.printer().firmware_retracted != target.firmware_retracted) tr.firmware_retraction(target.firmware_retracted);
  const Fixed now = Fixed::from_double(retracted_).rounded(ed), want = Fixed::from_double(in_retracted).rounded(ed);
  if (now < want) tr.extrude(now - want, moves_.e_feed);
  const Fixed z = target.at(kZ);
  const bool up = z > tr.printer().at(kZ);
  if (up && target.known[kZ]) tr.move_z(z);
  const bool z_off = tr.printer().at(kZ) != z;
  if (target.known[kX] && target.known[kY] &&
      (tr.printer().at(kX) != target.at(kX) || tr.printer().at(kY) != target.at(kY)))
    tr.move_xy(target.at(kX), target.at(kY));
  if (!up && z_off && target.known[kZ]) tr.move_z(z);
  if (now > want) tr.extrude(now - want, moves_.e_feed);
  if (!target.relative_e) tr.e_coordinate(target.at(kE));
  tr.feed_rate(target.feedrate);
  printer_ = tr.printer();
  retracted_ = in_retracted;
  behind_ = false;
}

}  // namespace gcode
