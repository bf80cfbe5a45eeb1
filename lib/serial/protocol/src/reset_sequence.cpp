#include "gcode/serial/protocol/reset_sequence.hpp"

#include <fmt/format.h>

namespace gcode::serial {

std::vector<std::string> reset_resume_lines(const ResetResume& how, const Precision& precision,
                                            const TransitionMoves& moves) {
  std::vector<std::string> out;
  Transition t(MachineState{}, precision, out, moves);
  if (how.target.inches) throw std::invalid_argument("inch units (G20): a resume works in millimetres only");
  if (!how.target.known[kX] || !how.target.known[kY] || !how.target.known[kZ])
    throw std::invalid_argument("the position to go back to was never known (no homing or move before it)");
  t.heaters(how.target, true);
  const int zd = precision.of('Z');
  const Fixed nozzle =
      std::isnan(how.nozzle_z) ? how.target.at(kZ) : Fixed::from_double(how.nozzle_z).rounded(zd);
  t.positioning(false);
  t.declare_z(nozzle);
  // The part's top may be above the nozzle (a lower object of several
  // printed one at a time): the lift clears the nozzle's own spot only,
  // the travel below clears everything.
  t.move_z(t.safe_z(nozzle));
  t.home_xy();
  Transition::Between way;
  way.top_z = how.top_z;
  way.retracted_to = how.retracted;
  way.prime = how.prime;
  t.between(how.target, way);
  return out;
}

std::string xy_homing_refusal(double z, const std::string& input) {
  const std::string file = input.empty() || input == "-" ? std::string("FILE") : input;
  return fmt::format(
      "this printer cannot home X and Y without Z (a delta homes all its towers at once), and the part stands on the "
      "bed: not resumed, nothing sent. To finish the part: measure its height (it stopped near Z {:.2f}), then\n"
      "  gc-relayer --list-candidates {:.2f} {}\n"
      "  gc-relayer --resume-from-z <measured Z> {} > resume.gcode\n"
      "and print resume.gcode (it heats, lifts, declares Z and goes on from the first layer above that height)",
      z, z, file, file);
}

}  // namespace gcode::serial
