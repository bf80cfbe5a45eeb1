// Questions about an overdue answer (gcode/serial/protocol/probe_backoff.hpp):
// at most kQuick in a row, each waiting twice as long; an answer starts over.
#include <catch2/catch.hpp>

#include "gcode/serial/protocol/probe_backoff.hpp"

using gcode::serial::ProbeBackoff;

TEST_CASE("probe backoff: each question waits twice as long, an answer starts over", "[serial][probe_backoff]") {
  ProbeBackoff backoff;
  CHECK(backoff.quick());
  CHECK(backoff.when(10, 1) == 10);  // the first as soon as the answer is overdue
  backoff.asked(10, 1);
  CHECK(backoff.when(10, 1) == 12);  // not before 10 + 2
  backoff.asked(12, 1);
  CHECK(backoff.when(10, 1) == 16);  // 12 + 4
  backoff.asked(16, 1);
  CHECK_FALSE(backoff.quick());  // kQuick in a row: only the timeout asks now
  backoff.answered();
  CHECK(backoff.quick());
  CHECK(backoff.when(20, 1) == 20);
}
