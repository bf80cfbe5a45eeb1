// The pauses of one print (gcode/serial/control/pause_log.hpp): each asked
// for, reached and resumed, and the seconds the print stood paused.
#include <catch2/catch.hpp>

#include "gcode/serial/control/pause_log.hpp"

using gcode::serial::PauseLog;

TEST_CASE("pause log: a pause asked, reached and resumed counts its paused seconds", "[serial][pause_log]") {
  PauseLog log;
  CHECK(log.empty());
  CHECK_FALSE(log.reaching());
  log.start("pause", 3, 10.0, -1);
  CHECK(log.reaching());
  CHECK(log.current().request == "pause");
  CHECK(log.current().layer == 3);
  CHECK(log.paused_seconds(11.0, true) == 0);  // not reached yet: nothing stood still
  log.reached(12.0);
  CHECK_FALSE(log.reaching());
  CHECK(log.paused_seconds(15.0, true) == Approx(3.0));
  log.resumed(20.0);
  CHECK(log.paused_seconds(25.0, false) == Approx(8.0));
  log.start("pause now", 4, 30.0, 5.5);
  CHECK(log.current().printer_request == 5.5);
  log.reached(31.0);
  CHECK(log.paused_seconds(33.0, true) == Approx(10.0));  // 8 resumed, 2 standing
}

TEST_CASE("pause log: a pause called off leaves no record", "[serial][pause_log]") {
  PauseLog log;
  log.start("pause", 1, 1.0, -1);
  log.reached(2.0);
  log.resumed(3.0);
  log.start("@pause", 2, 4.0, -1);
  log.call_off();
  REQUIRE(log.records().size() == 1);
  CHECK(log.records()[0].request == "pause");
  CHECK_FALSE(log.reaching());
}
