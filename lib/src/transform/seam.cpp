#include "gcode/transform/seam.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "gcode/transform/transition.hpp"

namespace gcode {

namespace {

void check_speed(double value, const char* option) {
  if (!(value > 0)) throw std::invalid_argument(std::string(option) + ": must be a number > 0");
}

}  // namespace

void SeamOptions::validate() const {
  if (!(lift >= 0)) throw std::invalid_argument("--lift: must be a number >= 0");
  if (!(retract >= 0)) throw std::invalid_argument("--retract: must be a number >= 0");
  check_speed(retract_speed, "--retract-speed");
  check_speed(travel_speed, "--travel-speed");
  check_speed(z_speed, "--z-speed");
}

Seam build_seam(const StreamPoint& from, const StreamPoint& to, const SeamOptions& o, const Precision& precision,
                bool convert_e) {
  const MachineState& a = from.state;
  const MachineState& b = to.state;
  if (a.inches || b.inches)
    throw std::invalid_argument("inch units (G20) at a seam: splicing works in millimetres only");
  if (!a.known[kX] || !a.known[kY] || !a.known[kZ])
    throw std::invalid_argument("the head position is not known where the block is joined (no homing or move yet)");

  Seam seam;
  const int zd = precision.of('Z'), ed = precision.of('E');
  const double rf = o.retract_speed * 60;
  Transition t(a, precision, seam.lines,
               {.lift = o.lift, .max_z = o.max_z, .z_feed = o.z_speed * 60, .xy_feed = o.travel_speed * 60,
                .e_feed = rf, .g0 = true});

  // 1. The seam's own moves are absolute. Marlin's G90 makes E absolute too,
  // so a stream that was relative in E by M83 gets it back at once.
  if (a.relative_xyz) {
    t.line("G90");
    if (a.relative_e && from.e_mode_set) t.line("M83");
  }

  // 2. Retract for the travel unless something is retracted already.
  const Fixed retracted_a = Fixed::from_double(from.retracted).rounded(ed);
  const Fixed retracted_b = Fixed::from_double(to.retracted).rounded(ed);
  Fixed travel_level = std::max(retracted_a, retracted_b);
  if (travel_level.is_zero() && !a.firmware_retracted && o.retract > 0) {
    if (a.uses_firmware_retraction) {
      t.firmware_retraction(true);
    } else {
      travel_level = Fixed::from_double(o.retract).rounded(ed);
    }
  }
  t.extrude(-(travel_level - retracted_a), rf);

  // 3. Above everything printed so far and above both sides.
  const Fixed z0 = a.at(kZ);
  const Fixed block_z = std::max(b.known[kZ] ? b.at(kZ) : Fixed(), Fixed::from_double(to.layer_z).rounded(zd));
  const Fixed base = std::max({z0, Fixed::from_double(from.top_z), block_z});
  const Fixed safe = o.max_z > 0 ? std::max(t.safe_z(base), base) : t.safe_z(base);
  seam.safe_z = safe.to_double();
  if (safe > z0) t.move_z(safe);

  // 4. The tool and the settings, the nozzle clear of the part.
  t.tool(b.tool);
  for (std::string& line : to.settings.lines_from(from.settings, b.tool)) t.line(line);

  // 5. Over to where the block starts, then down to its layer.
  if (b.known[kX] && b.known[kY] && (b.at(kX) != a.at(kX) || b.at(kY) != a.at(kY))) t.move_xy(b.at(kX), b.at(kY));
  if (block_z != safe) t.move_z(block_z);

  // 6. Back to the block's own retraction state.
  t.firmware_retraction(b.firmware_retracted);
  t.extrude(travel_level - retracted_b, rf);

  // 7. The block's modes, E coordinate and feed rate.
  if (b.relative_xyz) t.positioning(true);
  seam.e_mode_differs = t.printer().relative_e != b.relative_e;
  if (seam.e_mode_differs && !convert_e) {
    t.e_mode(b.relative_e);
    seam.e_mode_differs = false;
  }
  t.e_coordinate(b.at(kE));
  t.feed_rate(b.feedrate, true);
  seam.net_filament = t.net_filament().to_double();
  seam.relative_e = t.printer().relative_e;
  return seam;
}

}  // namespace gcode
