#include "gcode/transform/seam.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace gcode {

namespace {

void check_speed(double value, const char* option) {
  if (!(value > 0)) throw std::invalid_argument(std::string(option) + ": must be a number > 0");
}

// E moves in the printed side's mode, keeping the coordinate the firmware holds.
class SeamExtruder {
 public:
  SeamExtruder(bool relative, Fixed e, int decimals, int feed_decimals)
      : relative_(relative), e_(e), decimals_(decimals), feed_decimals_(feed_decimals) {}

  void move(std::vector<std::string>& out, Fixed amount, double feed_mm_min) {
    if (amount.is_zero()) return;
    e_ += amount;
    net_ += amount;
    b_.start("G1").fixed('E', relative_ ? amount : e_, decimals_).word('F', feed_mm_min, feed_decimals_);
    out.emplace_back(b_.view());
  }
  void set_relative(bool relative) { relative_ = relative; }
  bool relative() const { return relative_; }
  Fixed e() const { return e_; }
  Fixed net() const { return net_; }

 private:
  bool relative_;
  Fixed e_;
  int decimals_;
  int feed_decimals_;
  Fixed net_;
  LineBuilder b_;
};

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
  auto& out = seam.lines;
  LineBuilder lb;
  const int zd = precision.of('Z'), fd = precision.of('F');
  const double zf = o.z_speed * 60, xyf = o.travel_speed * 60, rf = o.retract_speed * 60;
  SeamExtruder e(a.relative_e, a.at(kE), precision.of('E'), fd);

  // 1. The seam's own moves are absolute. Marlin's G90 makes E absolute too,
  // so a stream that was relative in E by M83 gets it back at once.
  if (a.relative_xyz) {
    out.emplace_back("G90");
    e.set_relative(false);
    if (a.relative_e && from.e_mode_set) {
      out.emplace_back("M83");
      e.set_relative(true);
    }
  }

  // 2. Retract for the travel unless something is retracted already.
  const Fixed retracted_a = Fixed::from_double(from.retracted).rounded(precision.of('E'));
  const Fixed retracted_b = Fixed::from_double(to.retracted).rounded(precision.of('E'));
  Fixed travel_level = std::max(retracted_a, retracted_b);
  bool fw = a.firmware_retracted;
  if (travel_level.is_zero() && !fw && o.retract > 0) {
    if (a.uses_firmware_retraction) {
      out.emplace_back("G10");
      fw = true;
    } else {
      travel_level = Fixed::from_double(o.retract).rounded(precision.of('E'));
    }
  }
  e.move(out, -(travel_level - retracted_a), rf);

  // 3. Above everything printed so far and above both sides.
  const Fixed z0 = a.at(kZ);
  const Fixed block_z = std::max(b.known[kZ] ? b.at(kZ) : Fixed(), Fixed::from_double(to.layer_z).rounded(zd));
  Fixed base = std::max({z0, Fixed::from_double(from.top_z), block_z});
  Fixed safe = (base + Fixed::from_double(o.lift)).rounded(zd);
  if (o.max_z > 0) safe = std::max(std::min(safe, Fixed::from_double(o.max_z).rounded(zd)), base);
  seam.safe_z = safe.to_double();
  if (safe > z0) {
    lb.start("G0").fixed('Z', safe).word('F', zf, fd);
    out.emplace_back(lb.view());
  }

  // 4. The tool and the settings, the nozzle clear of the part.
  if (b.tool != a.tool) out.push_back(fmt::format("T{}", b.tool));
  for (std::string& line : to.settings.lines_from(from.settings, b.tool)) out.push_back(std::move(line));

  // 5. Over to where the block starts, then down to its layer.
  if (b.known[kX] && b.known[kY] && (b.at(kX) != a.at(kX) || b.at(kY) != a.at(kY))) {
    lb.start("G0").fixed('X', b.at(kX)).fixed('Y', b.at(kY)).word('F', xyf, fd);
    out.emplace_back(lb.view());
  }
  if (block_z != safe) {
    lb.start("G0").fixed('Z', block_z).word('F', zf, fd);
    out.emplace_back(lb.view());
  }

  // 6. Back to the block's own retraction state.
  if (fw != b.firmware_retracted) out.emplace_back(b.firmware_retracted ? "G10" : "G11");
  e.move(out, travel_level - retracted_b, rf);

  // 7. The block's modes, E coordinate and feed rate.
  if (b.relative_xyz) {
    out.emplace_back("G91");
    e.set_relative(true);
  }
  seam.e_mode_differs = e.relative() != b.relative_e;
  if (seam.e_mode_differs && !convert_e) {
    out.emplace_back(b.relative_e ? "M83" : "M82");
    e.set_relative(b.relative_e);
    seam.e_mode_differs = false;
  }
  if (e.e() != b.at(kE)) {
    lb.start("G92").fixed('E', b.at(kE));
    out.emplace_back(lb.view());
  }
  if (b.feedrate > 0) {
    lb.start("G1").fixed('F', Fixed::from_double(b.feedrate));
    out.emplace_back(lb.view());
  }
  seam.net_filament = e.net().to_double();
  seam.relative_e = e.relative();
  return seam;
}

}  // namespace gcode
