// The moves a pace probe's answer lets go (gcode/serial/protocol/probe_credit.hpp):
// doubling while probes find room, up to the planner, back to one when
// one is answered late.
#include <catch2/catch.hpp>

#include "gcode/serial/protocol/probe_credit.hpp"

using gcode::serial::ProbeCredit;

TEST_CASE("probe credit: doubles while probes find room, one again when late", "[serial][probe_credit]") {
  ProbeCredit credit;
  CHECK(credit.size() == 1);
  CHECK_FALSE(credit.take());
  CHECK(credit.answered(true, true, 16) == 0);  // the one move on its word
  CHECK(credit.size() == 2);
  CHECK(credit.answered(true, true, 16) == 1);
  CHECK(credit.size() == 4);
  CHECK(credit.take());
  CHECK_FALSE(credit.take());
  CHECK(credit.due());
  CHECK(credit.answered(true, true, 16) == 3);
  CHECK(credit.left() == 3);
  CHECK(credit.size() == 8);
  credit.full();  // a move waited for a block: the rest stops
  CHECK(credit.left() == 0);
  CHECK(credit.answered(true, true, 16) == 7);
  CHECK(credit.size() == 8);  // found room after a wait: no doubling
  CHECK(credit.left() == 7);
  CHECK_FALSE(credit.due());  // more than a quarter left
  CHECK(credit.answered(true, false, 16) == 0);  // not wanted: one move, the size kept
  CHECK(credit.size() == 8);
  CHECK(credit.answered(false, true, 16) == 0);  // late: the planner was full
  CHECK(credit.size() == 1);
  CHECK(credit.left() == 0);
  for (int i = 0; i < 10; ++i) credit.answered(true, true, 4);
  CHECK(credit.size() == 4);  // never beyond the planner's blocks
  CHECK(credit.left() <= 3);
}
