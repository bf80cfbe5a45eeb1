// Arc geometry: I/J and R forms, full circles, helices, and Marlin's P word
// (ARC_P_CIRCLES: P full turns before the arc to the end point), on real
// lines such as BambuStudio's spiral Z-hop "G3 Z.6 I1.217 J0 P1 F30000".
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "gcode/core/arc.hpp"
#include "gcode/core/line.hpp"

namespace {

constexpr double kPi = 3.141592653589793;

gcode::Arc arc_of(const std::string& text, double x0, double y0, double x1, double y1, double scale = 1) {
  gcode::Line line = gcode::Line::parse(text);
  REQUIRE((line.is_g(2) || line.is_g(3)));
  return gcode::make_arc(line, x0, y0, x1, y1, scale);
}

}  // namespace

TEST_CASE("arcs without P: half and quarter turns and the full circle back to the start", "[arc]") {
  gcode::Arc half = arc_of("G3 X10 Y0 I5 J0", 0, 0, 10, 0);
  REQUIRE(half.valid);
  CHECK(half.extra_turns == 0);
  CHECK(half.sweep == Approx(kPi));
  CHECK(half.length_xy() == Approx(5 * kPi));
  gcode::Arc quarter = arc_of("G2 X10 Y10 R10", 0, 0, 10, 10);
  CHECK(quarter.sweep == Approx(-kPi / 2));
  CHECK(quarter.length_xy() == Approx(10 * kPi / 2));
  gcode::Arc circle = arc_of("G2 I-5 J0", 10, 0, 10, 0);
  CHECK(circle.sweep == Approx(-2 * kPi));
  CHECK(circle.length_xy() == Approx(10 * kPi));
}

TEST_CASE("BambuStudio spiral lift read as Marlin ARC_P_CIRCLES: P1 back to its start point is two turns", "[arc]") {
  // From (100,50) at Z 0.4: centre 1.217 mm to the right, up to Z 0.6.
  gcode::Arc a = arc_of("G3 Z.6 I1.217 J0 P1 F30000", 100, 50, 100, 50);
  REQUIRE(a.valid);
  CHECK(a.extra_turns == 1);
  CHECK(a.radius == Approx(1.217));
  CHECK(a.cx == Approx(101.217));
  CHECK(a.cy == Approx(50));
  CHECK(a.sweep == Approx(4 * kPi));  // the full circle of equal start and end, plus one
  CHECK(a.length_xy() == Approx(4 * kPi * 1.217));
  CHECK(a.length(0.2) == Approx(std::sqrt(std::pow(4 * kPi * 1.217, 2) + 0.04)));
  // Halfway through the sweep the head is back over the start point.
  double mid = a.start_angle + a.sweep / 2;
  CHECK(a.cx + a.radius * std::cos(mid) == Approx(100));
  CHECK(std::fabs(a.cy + a.radius * std::sin(mid) - 50) < 1e-9);
  // The same line clockwise, as BambuStudio also writes it.
  gcode::Arc cw = arc_of("G2 Z.6 I.86 J.86 P1 F10000", 0, 0, 0, 0);
  CHECK(cw.sweep == Approx(-4 * kPi));
  CHECK(cw.length_xy() == Approx(4 * kPi * std::hypot(0.86, 0.86)));
}

TEST_CASE("P1 and P2 add whole turns to partial arcs in their own direction", "[arc]") {
  gcode::Arc ccw1 = arc_of("G3 X10 Y0 I5 J0 P1", 0, 0, 10, 0);
  CHECK(ccw1.sweep == Approx(kPi + 2 * kPi));
  CHECK(ccw1.length_xy() == Approx(3 * kPi * 5));
  gcode::Arc ccw2 = arc_of("G3 X10 Y0 I5 J0 P2", 0, 0, 10, 0);
  CHECK(ccw2.length_xy() == Approx(5 * kPi * 5));
  gcode::Arc cw2 = arc_of("G2 X10 Y10 R10 P2", 0, 0, 10, 10);  // R form: a quarter turn plus two
  CHECK(cw2.sweep == Approx(-(kPi / 2 + 4 * kPi)));
  CHECK(cw2.length_xy() == Approx(10 * 4.5 * kPi));
  CHECK(arc_of("G3 X10 Y0 I5 J0 P0", 0, 0, 10, 0).sweep == Approx(kPi));
}

TEST_CASE("a helix with P shares its rise along all its turns", "[arc]") {
  // r 5, one circle plus P1 = two turns, rising 1 mm.
  gcode::Arc a = arc_of("G2 Z1 I5 J0 P1", 0, 0, 0, 0);
  double xy = 2 * 2 * kPi * 5;
  CHECK(a.length_xy() == Approx(xy));
  CHECK(a.length(1) == Approx(std::sqrt(xy * xy + 1)));
  CHECK(a.length(-1) == Approx(a.length(1)));
  CHECK(a.length(0) == Approx(xy));
}

TEST_CASE("inches scale the centre and P stays a count of turns", "[arc]") {
  gcode::Arc a = arc_of("G3 X0.5 Y0 I0.25 J0 P1", 0, 0, 12.7, 0, 25.4);
  CHECK(a.radius == Approx(6.35));
  CHECK(a.length_xy() == Approx(3 * kPi * 6.35));
}

TEST_CASE("a P that is not a whole number from 0 to 100 is not an arc Marlin would run", "[arc]") {
  for (const char* line : {"G3 X10 Y0 I5 J0 P-1", "G3 X10 Y0 I5 J0 P1.5", "G3 X10 Y0 I5 J0 P101"}) {
    INFO(line);
    CHECK_FALSE(arc_of(line, 0, 0, 10, 0).valid);
  }
  CHECK(arc_of("G3 X10 Y0 I5 J0 P100", 0, 0, 10, 0).extra_turns == 100);
  CHECK_FALSE(gcode::make_arc(0, 0, 10, 0, false, true, 5, 0, 0, -1).valid);
  CHECK_FALSE(gcode::make_arc(0, 0, 10, 0, false, true, 5, 0, 0, gcode::kMaxArcTurns + 1).valid);
}
