// When an answer is overdue (gcode/serial/protocol/answer_clock.hpp): bytes cross
// the link at the baud rate, a move is answered when the planner has room,
// a command that is not a move when the planner is empty, a long command
// while keepalives come; every figure below follows from those rules.
#include <catch2/catch.hpp>

#include "gcode/serial/protocol/answer_clock.hpp"

using namespace gcode::serial;

namespace {

// 25000 bytes per second (250000 baud): 40 us per byte; the margin is
// 0.1 s plus 64 byte times.
constexpr double kByte = 1.0 / 25000;
constexpr double kClockMargin = 0.1 + 64 * kByte;

AnswerClock::Wait move(int moves = 1, double motion = 0) {
  AnswerClock::Wait w;
  w.moves = moves;
  w.motion = motion;
  return w;
}

AnswerClock::Wait other(double motion = 0) {
  AnswerClock::Wait w;
  w.empty = true;
  w.motion = motion;
  return w;
}

}  // namespace

TEST_CASE("answer clock: bytes reach the printer one byte time apart after what was written before", "[serial]") {
  AnswerClock c(25000, 1);
  CHECK(c.written(40, 1.0) == Approx(1.0016));
  CHECK(c.written(10, 1.0) == Approx(1.0020));     // queued behind the first line
  CHECK(c.arrival_of(10) == Approx(1.0016));       // the byte 10 before the last one
  CHECK(c.written(5, 2.0) == Approx(2.0002));      // the link was idle
  AnswerClock unlimited(0, 1);                     // a pseudo-terminal
  CHECK(unlimited.written(1000, 3.0) == 3.0);
  CHECK(unlimited.margin() == Approx(0.1));
  // A simulated printer 10 times faster: its 250000 baud carry 250000 bytes per wall second.
  AnswerClock scaled(250000, 10);
  CHECK(scaled.written(250, 0) == Approx(0.001));
}

TEST_CASE("answer clock: a line is due after it arrived and the answer before it came", "[serial]") {
  AnswerClock c(25000, 1);
  CHECK(c.due(1.0, move()) == Approx(1.0 + kClockMargin));
  c.answered(0, 2.0);  // a command without motion answered at 2 s
  CHECK(c.ready(1.0, move()) == Approx(2.0));
  CHECK(c.due(1.0, move()) == Approx(2.0 + kClockMargin));
  CHECK(c.due(3.0, other()) == Approx(3.0 + kClockMargin));
}

TEST_CASE("answer clock: a move is answered when the planner has room and others when it is empty", "[serial]") {
  AnswerClock c(0, 1, 4);  // a 4-block planner
  // Four moves of 1 s answered at once: with the safety factor 1.5 they end
  // at 1.5, 3, 4.5 and 6 s.
  for (int i = 0; i < 4; ++i) c.answered(1.0, 0.0);
  CHECK(c.planner_empty() == Approx(6.0));
  CHECK(c.ready(0, move(1)) == Approx(1.5));  // room for one block when the oldest ends
  CHECK(c.ready(0, move(2)) == Approx(3.0));  // for two, when the second ends
  CHECK(c.ready(0, move(4)) == Approx(6.0));
  CHECK(c.ready(0, move(5, 2.0)) == Approx(6.0 + 3.0));  // more than the planner: empty, then the moves ahead
  CHECK(c.ready(0, other()) == Approx(6.0));
  CHECK(c.ready(0, other(1.0)) == Approx(7.5));  // a move ahead in flight enters the planner first
  // Fewer moves than blocks: room at once.
  AnswerClock d(0, 1, 4);
  d.answered(1.0, 0.0);
  d.answered(1.0, 0.0);
  CHECK(d.ready(0.5, move(1)) == Approx(0.5));
  CHECK(d.ready(0.5, move(2)) == Approx(0.5));
  CHECK(d.ready(0.5, move(3)) == Approx(1.5));
  // A time scale of 10 makes the moves ten times shorter on the wall clock.
  AnswerClock e(0, 10, 4);
  e.answered(1.0, 0.0);
  CHECK(e.planner_empty() == Approx(0.15));
}

TEST_CASE("answer clock: a move answered sooner than the model says pulls the end times back", "[serial]") {
  AnswerClock c(0, 1, 2);
  c.answered(1.0, 0.0);  // ends 1.5
  c.answered(1.0, 0.0);  // ends 3.0
  // The third move got the first one's block at 0.5 s, not 1.5: the model
  // runs 1 s long and every end time moves back by that.
  c.answered(1.0, 0.5);
  CHECK(c.planner_empty() == Approx(3.5));  // 2.0 for the second, then 1.5 more
  CHECK(c.ready(0.5, move(1)) == Approx(2.0));
  // The freed block took 0.5 s of its estimated 1: one sample is not enough
  // to believe the printer faster.
  CHECK(c.motion_factor() == Approx(1.5));
}

TEST_CASE("answer clock: the estimates are scaled by how fast the printer runs its moves", "[serial]") {
  AnswerClock c(0, 1, 2);
  c.answered(1.0, 0.0);
  c.answered(1.0, 0.0);
  // Moves estimated at 1 s answered every 10 ms with the planner full: they
  // take no time (a simulated printer), and soon count for almost nothing.
  for (int i = 1; i <= 100; ++i) c.answered(1.0, 0.01 * i);
  CHECK(c.motion_factor() == Approx(AnswerClock::kMinFactor));
  CHECK(c.planner_empty() < 1.0 + 0.05);
  // But never for less than their length at their feed rate.
  c.answered(1.0, 1.01, 0.5);
  CHECK(c.planner_empty() >= 1.01 + 0.5);
  // One move that took its full time makes the printer slow again at once.
  c.answered(1.0, 2.0);
  c.answered(1.0, 3.0);
  CHECK(c.motion_factor() == Approx(1.25));
  // Answers a second apart for moves estimated at 1 s: 1.25 times that.
  for (int i = 4; i < 30; ++i) c.answered(1.0, i);
  CHECK(c.motion_factor() == Approx(1.25));
  // Slower than estimated: at most 1.5.
  for (int i = 0; i < 30; ++i) c.answered(1.0, 30 + 3 * i);
  CHECK(c.motion_factor() == Approx(1.5));
}

TEST_CASE("answer clock: the planner size can be learnt and keeps the newest moves", "[serial]") {
  AnswerClock c(0, 1, 4);
  for (int i = 0; i < 4; ++i) c.answered(1.0, 0.0);  // ends 1.5, 3, 4.5, 6
  c.set_planner_blocks(2);                            // keeps 4.5 and 6
  CHECK(c.ready(0, move(1)) == Approx(4.5));
  CHECK(c.ready(0, move(2)) == Approx(6.0));
  c.set_planner_blocks(8);
  CHECK(c.ready(0, move(7)) == Approx(4.5));
  CHECK(c.ready(0, move(6)) == Approx(0));
  c.answered(1.0, 0.0);
  CHECK(c.planner_empty() == Approx(7.5));
  CHECK(c.ready(0, move(6)) == Approx(4.5));
}

TEST_CASE("answer clock: long commands are due 1.5 keepalive intervals after the last sign of life", "[serial]") {
  AnswerClock c(25000, 1);
  AnswerClock::Wait heat;
  heat.empty = true;
  heat.unbounded = true;
  // Nothing heard yet: Marlin's 2 s keepalive is assumed.
  CHECK(c.due(5.0, heat) == Approx(5.0 + 3.0 + kClockMargin));
  c.keepalive(10.0);
  c.keepalive(11.0);  // temperature reports every second while heating
  CHECK(c.due(5.0, heat) == Approx(11.0 + 1.5 + kClockMargin));
  c.keepalive(12.0);
  CHECK(c.due(5.0, heat) == Approx(12.0 + 1.5 + kClockMargin));
  // A keepalive after the last answer also holds back a bounded command.
  CHECK(c.due(5.0, move()) == Approx(12.0 + 1.5 + kClockMargin));
  c.answered(0, 13.0);
  CHECK(c.due(13.0, move()) == Approx(13.0 + kClockMargin));
  // A gap of minutes between two long commands is not an interval.
  c.keepalive(300.0);
  c.keepalive(301.0);
  CHECK(c.due(0, heat) == Approx(301.0 + 1.5 + kClockMargin));
}

TEST_CASE("answer clock: the quiet time after a resend covers the stale bytes twice", "[serial]") {
  AnswerClock c(25000, 1);
  CHECK(c.quiet(136) == Approx(2 * 200 * kByte));
  CHECK(c.quiet(0) == Approx(2 * 64 * kByte));
  CHECK(c.quiet(100000) == Approx(0.5));
  CHECK(AnswerClock(2.5e8, 1).quiet(10) == Approx(0.002));
  CHECK(AnswerClock(0, 1).quiet(10) == Approx(0.02));  // an unknown link: a fixed 20 ms
}
