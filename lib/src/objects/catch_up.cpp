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
  // only at the start of an extrusion (no ooze over what was left out).
  const Fixed in_depth = Fixed::from_double(in_retracted).rounded(ed);
  auto depth_to_input = [&](bool prime) {
    const Fixed now = Fixed::from_double(retracted_).rounded(ed);
    if (now == in_depth || (now > in_depth && !prime)) return;
    tr.extrude(now - in_depth, moves_.e_feed);
    retracted_ = in_retracted;
  };
  depth_to_input(false);
  // What the line's own words leave to the position it starts from.
  const bool fw_move = t.move.kind == MoveKind::FirmwareRetract || t.move.kind == MoveKind::FirmwareUnretract;
  const bool x = line_sets(line, 'X') && !fw_move, y = line_sets(line, 'Y') && !fw_move, z_word = line_sets(line, 'Z') && !fw_move;
  // An extrusion, an arc or a wipe (E while moving) starts where the input is.
  const bool whole = t.move.extruding || t.move.kind == MoveKind::Arc || (t.move.filament != 0 && t.move.moves_head());
  const bool needs_xy = whole || (in.relative_xyz ? (x || y) : (x != y));
  const bool needs_z = whole || (in.relative_xyz ? (x || y || z_word) : ((x || y) && !z_word));
  const Fixed z = in.at(kZ);
  const bool xy_off = tr.printer().at(kX) != in.at(kX) || tr.printer().at(kY) != in.at(kY);
  const bool z_off = tr.printer().at(kZ) != z;
  const bool move_xy = needs_xy && xy_off && in.known[kX] && in.known[kY];
  const bool move_z = needs_z && z_off && in.known[kZ];
  // Moves are written absolute; a G91 stretch gets its G91 back.
  const bool relative = tr.printer().relative_xyz && (move_xy || move_z);
  if (relative) tr.positioning(false);
  if (move_z && move_xy && z > tr.printer().at(kZ)) tr.move_z(z);
  if (move_xy) tr.move_xy(in.at(kX), in.at(kY));
  if (move_z && tr.printer().at(kZ) != z) tr.move_z(z);
  if (relative) tr.positioning(true);
  if (t.move.extruding) depth_to_input(true);
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
  const bool relative = tr.printer().relative_xyz;
  if (relative) tr.positioning(false);
  if (up && target.known[kZ]) tr.move_z(z);
  const bool z_off = tr.printer().at(kZ) != z;
  if (target.known[kX] && target.known[kY] &&
      (tr.printer().at(kX) != target.at(kX) || tr.printer().at(kY) != target.at(kY)))
    tr.move_xy(target.at(kX), target.at(kY));
  if (!up && z_off && target.known[kZ]) tr.move_z(z);
  if (relative) tr.positioning(true);
  if (now > want) tr.extrude(now - want, moves_.e_feed);
  if (!target.relative_e) tr.e_coordinate(target.at(kE));
  tr.feed_rate(target.feedrate);
  printer_ = tr.printer();
  retracted_ = in_retracted;
  behind_ = false;
}

}  // namespace gcode
