#include "gcode/transform/transition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gcode/core/line.hpp"

namespace gcode {

Transition::Transition(const MachineState& from, const Precision& precision, std::vector<std::string>& out,
                       TransitionMoves moves)
    : now_(from), precision_(precision), out_(&out), moves_(moves) {}

void Transition::line(std::string_view text) {
  now_.apply(Line::parse(text));
  out_->emplace_back(text);
}

void Transition::positioning(bool relative) {
  if (now_.relative_xyz != relative) line(relative ? "G91" : "G90");
}

void Transition::e_mode(bool relative, bool force) {
  if (force || now_.relative_e != relative) line(relative ? "M83" : "M82");
}

void Transition::e_coordinate(Fixed e, bool force) {
  if (force || now_.at(kE) != e) line(b_.start("G92").fixed('E', e).view());
}

void Transition::feed_rate(double mm_min, bool force) {
  if (mm_min > 0 && (force || now_.feedrate != mm_min)) line(b_.start("G1").fixed('F', Fixed::from_double(mm_min)).view());
}

void Transition::firmware_retraction(bool retracted) {
  if (now_.firmware_retracted != retracted) line(retracted ? "G10" : "G11");
}

void Transition::tool(int tool) {
  if (now_.tool != tool) line(fmt::format("T{}", tool));
}

void Transition::move(char axis1, Fixed v1, char axis2, Fixed v2, bool two, double feed) {
  b_.start(moves_.g0 ? "G0" : "G1").fixed(axis1, v1);
  if (two) b_.fixed(axis2, v2);
  line(b_.word('F', feed, precision_.of('F')).view());
}

void Transition::move_z(Fixed z) { move('Z', z, 0, Fixed(), false, moves_.z_feed); }

void Transition::move_xy(Fixed x, Fixed y) { move('X', x, 'Y', y, true, moves_.xy_feed); }

void Transition::home_xy() { line("G28 X Y"); }

void Transition::declare_z(Fixed z) { line(b_.start("G92").fixed('Z', z).view()); }

Fixed Transition::safe_z(Fixed base) const {
  const int zd = precision_.of('Z');
  Fixed safe = (base + Fixed::from_double(moves_.lift)).rounded(zd);
  if (moves_.max_z > 0) safe = std::min(safe, Fixed::from_double(moves_.max_z).rounded(zd));
  return safe;
}

void Transition::extrude(Fixed amount, double feed_mm_min) {
  const int ed = precision_.of('E'), fd = precision_.of('F');
  // Whole 150 mm pieces then the rest, so every piece is a short decimal.
  const Fixed chunk = Fixed::from_int(static_cast<std::int64_t>(kMaxExtrudeChunk));
  Fixed left = amount;
  while (!left.is_zero()) {
    Fixed piece = left > chunk ? chunk : (left < -chunk ? -chunk : left);
    left -= piece;
    net_ += piece;
    b_.start("G1").fixed('E', now_.relative_e ? piece : now_.at(kE) + piece, ed).word('F', feed_mm_min, fd);
    line(b_.view());
  }
}

void Transition::extrude_mm(double amount_mm, double speed_mm_s) {
  extrude(Fixed::from_double(amount_mm).rounded(precision_.of('E')), speed_mm_s * 60);
}

void Transition::hotend(int tool, double target, bool wait, bool name_tool) {
  b_.start(wait ? "M109" : "M104");
  if (name_tool) b_.word('T', tool, 0);
  // M109 S waits only while heating (Marlin); R waits for cooling too.
  const bool cooling = tool >= 0 && tool < static_cast<int>(now_.hotend_target.size()) &&
                       now_.hotend_target[static_cast<std::size_t>(tool)] > target;
  line(b_.word(wait && cooling ? 'R' : 'S', target, 1).view());
}

void Transition::bed(double target, bool wait) {
  const bool cooling = now_.bed_target > target;
  line(b_.start(wait ? "M190" : "M140").word(wait && cooling ? 'R' : 'S', target, 1).view());
}

void Transition::fan(double speed) {
  if (speed > 0) {
    line(b_.start("M106").word('S', speed, 1).view());
  } else {
    line("M107");
  }
}

void Transition::heaters(const MachineState& to, bool wait_rising) {
  if (now_.bed_target != to.bed_target) bed(to.bed_target, wait_rising && to.bed_target > now_.bed_target);
  for (std::size_t t = 0; t < to.hotend_target.size(); ++t) {
    const double target = to.hotend_target[t];
    if (now_.hotend_target[t] == target) continue;
    hotend(static_cast<int>(t), target, wait_rising && target > now_.hotend_target[t],
           static_cast<int>(t) != to.tool);
  }
}

void Transition::speed_factor(double percent) {
  if (now_.speed_factor != percent) line(b_.start("M220").word('S', percent, 1).view());
}

void Transition::flow_factor(double percent) {
  if (now_.flow_factor != percent) line(b_.start("M221").word('S', percent, 1).view());
}

void Transition::between(const MachineState& to, const Between& how) {
  if (now_.inches || to.inches) throw std::invalid_argument("inch units (G20): transitions work in millimetres only");
  if (!to.known[kX] || !to.known[kY] || !to.known[kZ])
    throw std::invalid_argument("the position to go to is not known (no homing or move before it)");
  if (!now_.known[kZ] && std::isnan(how.nozzle_z))
    throw std::invalid_argument("the printer does not know its Z and it cannot be homed over the part: give the height");
  heaters(to, true);
  positioning(false);
  if (!now_.known[kX] || !now_.known[kY]) home_xy();
  if (!now_.known[kZ]) declare_z(Fixed::from_double(how.nozzle_z).rounded(precision_.of('Z')));
  tool(to.tool);
  // The E coordinate is the printer's from here on: only differences count.
  const int ed = precision_.of('E');
  const Fixed retracted_from = Fixed::from_double(how.retracted_from).rounded(ed);
  const Fixed retracted_to = Fixed::from_double(how.retracted_to).rounded(ed);
  const Fixed z0 = now_.at(kZ);
  const Fixed base = std::max({z0, Fixed::from_double(how.top_z), to.at(kZ)});
  const Fixed safe = std::max(safe_z(base), base);
  if (safe > z0) move_z(safe);
  if (now_.at(kX) != to.at(kX) || now_.at(kY) != to.at(kY)) move_xy(to.at(kX), to.at(kY));
  if (safe != to.at(kZ)) move_z(to.at(kZ));
  extrude(Fixed::from_double(how.prime).rounded(ed) + retracted_from - retracted_to, moves_.e_feed);
  firmware_retraction(to.firmware_retracted);
  positioning(to.relative_xyz);
  if (to.e_mode_set || now_.relative_e != to.relative_e) e_mode(to.relative_e, to.e_mode_set);
  e_coordinate(to.at(kE), !to.relative_e);
  feed_rate(to.feedrate);
  if (now_.fan != to.fan) fan(to.fan);
  speed_factor(to.speed_factor);
  flow_factor(to.flow_factor);
}

}  // namespace gcode
