// gc-send's progress (gcode/serial/job/progress.hpp): the status file is JSON a
// script can read (unknown figures are null), and the line shows the same.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <string>

#include "gcode/serial/job/progress.hpp"

TEST_CASE("progress: the status JSON parses and names what the line shows", "[serial]") {
  gcode::serial::ProgressSnapshot s;
  s.state = "paused";
  s.layer = 12;
  s.layers = 40;
  s.percent = 31;
  s.lines = 812;
  s.elapsed = 42;
  s.eta = 93;
  s.last_pause_mm = 2.9;
  s.last_pause_s = 0.14;
  s.last_pause_layer = 11;
  s.last_paused_before = 12;
  s.temperatures = "T:205.00 /205.00 B:60.00 /60.00";
  s.resets = 1;
  s.redone_mm = 3.14;
  auto j = nlohmann::json::parse(gcode::serial::progress_json(s));
  CHECK(j["state"] == "paused");
  CHECK(j["layer"] == 12);
  CHECK(j["layers"] == 40);
  CHECK(j["lines"] == 812);
  CHECK(j["eta"] == 93);
  CHECK(j["last_paused_before"] == 12);
  CHECK(j["resets"] == 1);
  CHECK(j["redone_mm"] == Approx(3.1));
  CHECK(j["temperatures"] == "T:205.00 /205.00 B:60.00 /60.00");
  s.percent = -1;
  s.eta = -1;
  j = nlohmann::json::parse(gcode::serial::progress_json(s));
  CHECK(j["percent"].is_null());
  CHECK(j["eta"].is_null());
  std::string line = gcode::serial::progress_line(s);
  CHECK(line.find("layer 12/40") != std::string::npos);
  CHECK(line.find("ETA") == std::string::npos);
  CHECK(line.find("last pause 2.9 mm") != std::string::npos);
  CHECK(line.find("1 reset (3.1 mm again)") != std::string::npos);
}

TEST_CASE("progress: the ETA from the estimator, paced by the print so far", "[serial]") {
  using gcode::serial::estimated_remaining;
  // A 1000 s estimate, 400 s of it handed over in 200 s of printing (a time
  // scale of 2, a faster printer): 600 estimated seconds left take 300.
  CHECK(estimated_remaining(1000, 400, 200) == Approx(300));
  // Slower than the model: 400 estimated seconds took 600.
  CHECK(estimated_remaining(1000, 400, 600) == Approx(900));
  // Too early to tell, no estimate, or past it.
  CHECK(estimated_remaining(1000, 40, 200) < 0);
  CHECK(estimated_remaining(1000, 400, 4) < 0);
  CHECK(estimated_remaining(0, 400, 200) < 0);
  CHECK(estimated_remaining(1000, 1200, 600) == Approx(0));
}

TEST_CASE("progress: the print's ETA paces from layer 1 on, without the pauses", "[serial]") {
  gcode::serial::PrintEta eta;
  eta.set_estimate(1100);
  // The start code: no pace yet, the rate of the input (20 % in 10 s: 40 s).
  CHECK(eta.remaining(10, 50, 0, 20, 10) == Approx(40));
  CHECK(eta.remaining(10, 50, 0, -1, 10) < 0);
  // Layer 1 at 100 s, 100 estimated seconds handed over (the heating took
  // wall time the estimate has not), 5 s stood paused by then.
  eta.layer_one(100, 100, 5);
  eta.layer_one(150, 300, 5);  // once only
  REQUIRE(eta.pacing());
  // 400 estimated seconds more in 230 wall seconds, 30 of them paused: a
  // pace of 0.5, 600 estimated seconds left take 300.
  CHECK(eta.remaining(330, 500, 35, 50, 330) == Approx(300));
  // Too early to tell from the estimate: the rate of the input.
  CHECK(eta.remaining(102, 101, 5, 50, 102) == Approx(102));
  // A swapped-in file has no estimate: the rate of its input only.
  eta.set_estimate(0);
  CHECK(eta.remaining(330, 500, 35, 75, 330) == Approx(110));
}
