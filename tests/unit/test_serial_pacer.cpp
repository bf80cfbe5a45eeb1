// The sender's pacer (serial/pacer.hpp): no more moves ahead of the nozzle
// than the planner holds.
#include <catch2/catch.hpp>

#include "gcode/serial/pacer.hpp"

using namespace gcode::serial;

TEST_CASE("pacer: moves in flight and planned moves still running fill the planner", "[serial][pacer]") {
  Pacer p;
  CHECK_FALSE(p.blocked(0, 3, 4));
  CHECK(p.blocked(0, 4, 4));
  CHECK(p.wake() == Pacer::kNever);  // an answer will come
  // Two answered moves of 1 s each run one after the other: until 1 and 2.
  p.planned(1, 0, 4, 1);
  p.planned(1, 0, 4, 1);
  CHECK(p.blocked(0.5, 2, 4));
  CHECK_FALSE(p.blocked(1.5, 2, 4));  // the first has ended
  CHECK_FALSE(p.blocked(2.5, 3, 4));
}

TEST_CASE("pacer: with nothing in flight it wakes when a block ends", "[serial][pacer]") {
  Pacer p;
  for (int i = 0; i < 4; ++i) p.planned(2, 0, 4, 1);  // ends at 2, 4, 6, 8
  CHECK(p.blocked(1, 0, 4));
  CHECK(p.wake() == 2);
  p.clear_wake();
  CHECK(p.wake() == Pacer::kNever);
}

TEST_CASE("pacer: a simulated printer's time scale shortens the moves", "[serial][pacer]") {
  Pacer p;
  p.planned(10, 0, 2, 20);  // 10 printer seconds at 20 x: 0.5 s
  CHECK(p.blocked(0.4, 1, 2));
  CHECK_FALSE(p.blocked(0.6, 1, 2));
  // A move answered after the planner ran dry starts then, not after the last end.
  p.planned(10, 5, 2, 20);
  CHECK(p.blocked(5.4, 1, 2));
  CHECK_FALSE(p.blocked(5.6, 1, 2));
}
