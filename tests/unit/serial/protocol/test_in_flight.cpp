// The sender's in-flight ledger (serial/in_flight.hpp): each "ok" frees what
// it answers for, and where a stream could mean two things, the least.
#include <catch2/catch.hpp>

#include "gcode/serial/protocol/in_flight.hpp"
#include "gcode/serial/protocol/protocol.hpp"

using namespace gcode::serial;
using AnswerKind = InFlight::Answer::Kind;

namespace {

// Lines 1..n of 10 bytes each, then `questions` M105s of the sender's (numbered on).
InFlight lines(int n, int questions = 0) {
  InFlight f;
  std::uint64_t end = 0;
  for (int i = 1; i <= n; ++i) f.push(i, 10, false, end += 10);
  for (int i = 0; i < questions; ++i) f.push(n + 1 + i, 5, true, end += 5, 0, InFlight::Own::Question);
  return f;
}

}  // namespace

TEST_CASE("in flight: a plain ok answers the oldest entry", "[serial][in_flight]") {
  InFlight f = lines(3);
  InFlight::Answer a = f.answer_to(parse_response("ok"), false);
  CHECK(a.kind == AnswerKind::Through);
  CHECK(a.index == 0);
  CHECK(f.bytes() == 30);
  CHECK(f.lines() == 3);
  CHECK(f.pop_front().number == 1);
  CHECK(f.bytes() == 20);
}

TEST_CASE("in flight: an ok with nothing in flight is stray", "[serial][in_flight]") {
  InFlight f;
  CHECK(f.answer_to(parse_response("ok"), false).kind == AnswerKind::Stray);
  CHECK(f.answer_to(parse_response("ok N3 P15 B3"), true).kind == AnswerKind::Stray);
}

TEST_CASE("in flight: ok T: answers through the M105, and our questions right behind it", "[serial][in_flight]") {
  InFlight f = lines(2, 2);
  InFlight::Answer a = f.answer_to(parse_response("ok T:200.0 /200.0 B:60.0 /60.0"), false);
  CHECK(a.kind == AnswerKind::Through);
  CHECK(a.index == 3);
  CHECK(f.asking());
  // Without an M105 in flight it answers a question written off: nothing.
  CHECK(lines(3).answer_to(parse_response("ok T:200.0 /200.0"), false).kind == AnswerKind::Stray);
}

TEST_CASE("in flight: with ADVANCED_OK, ok N<n> answers through line n, an ok without N only a question",
          "[serial][in_flight]") {
  InFlight f = lines(4, 1);
  InFlight::Answer a = f.answer_to(parse_response("ok N2 P15 B3"), true);
  CHECK(a.kind == AnswerKind::Through);
  CHECK(a.index == 1);
  CHECK(f.answer_to(parse_response("ok N9 P15 B3"), true).index == 4);  // everything sent before it, the question too
  a = f.answer_to(parse_response("ok"), true);
  CHECK(a.kind == AnswerKind::Question);
  CHECK(a.index == 4);
  CHECK(lines(4).answer_to(parse_response("ok"), true).kind == AnswerKind::Stray);  // frees no line
  CHECK(lines(4).answer_to(parse_response("ok N0 P15 B3"), true).kind == AnswerKind::Stray);
  f.erase(4);
  CHECK_FALSE(f.asking());
  CHECK(f.bytes() == 40);
}

TEST_CASE("in flight: a resend of line n drops n on and the questions behind it", "[serial][in_flight]") {
  InFlight f = lines(5, 1);
  CHECK(f.drop_from(3) == 35);
  CHECK(f.size() == 2);
  CHECK(f.bytes() == 20);
  CHECK_FALSE(f.asking());
}

TEST_CASE("in flight: entries arrive once their last byte is written", "[serial][in_flight]") {
  InFlight f = lines(3);
  f.written(25, [](std::size_t after) { return 100.0 + static_cast<double>(after); });
  CHECK(f[0].arrival == 115);
  CHECK(f[1].arrival == 105);
  CHECK(f[2].arrival == InFlight::kNotArrived);
  f.written(30, [](std::size_t) { return 200.0; });
  CHECK(f[0].arrival == 115);  // once
  CHECK(f[2].arrival == 200);
}

TEST_CASE("in flight: the marked lines, questions and probes are counted as entries come and go",
          "[serial][in_flight]") {
  // Against a walk of the entries, after every kind of change.
  auto walked = [](const InFlight& f, InFlight::Mark m) {
    std::size_t n = 0;
    for (const InFlight::Entry& e : f) n += (e.marks & m) ? 1 : 0;
    return n;
  };
  auto agrees = [&](const InFlight& f) {
    for (InFlight::Mark m : {InFlight::kLongRunning, InFlight::kUnbounded, InFlight::kSilentWait, InFlight::kMove})
      REQUIRE(f.marked(m) == walked(f, m));
    std::size_t questions = 0, probes = 0;
    for (const InFlight::Entry& e : f) {
      questions += e.own == InFlight::Own::Question;
      probes += e.own == InFlight::Own::PaceProbe;
    }
    REQUIRE(f.lines() == f.size() - questions);
    REQUIRE(f.asking() == (questions > 0));
    REQUIRE(f.probing() == (probes > 0));
  };
  InFlight f;
  std::uint64_t end = 0;
  f.push(1, 10, false, end += 10, InFlight::kMove);
  f.push(2, 10, false, end += 10, InFlight::kLongRunning | InFlight::kUnbounded);
  f.push(3, 4, false, end += 4, 0, InFlight::Own::PaceProbe);
  f.push(4, 10, false, end += 10, InFlight::kSilentWait);
  f.push(5, 5, true, end += 5, 0, InFlight::Own::Question);
  f.push(6, 10, false, end += 10, InFlight::kMove);
  agrees(f);
  CHECK(f.marked(InFlight::kMove) == 2);
  CHECK(f.marked(InFlight::kLongRunning) == 1);
  CHECK(f.pop_front().number == 1);
  agrees(f);
  CHECK(f.marked(InFlight::kMove) == 1);
  f.erase(1);  // the probe
  agrees(f);
  CHECK_FALSE(f.probing());
  CHECK(f.drop_from(4) == 25);  // line 4, the question behind it and line 6
  agrees(f);
  CHECK(f.marked(InFlight::kSilentWait) == 0);
  CHECK(f.marked(InFlight::kMove) == 0);
  CHECK(f.marked(InFlight::kUnbounded) == 1);
  f.clear();
  agrees(f);
  CHECK(f.marked(InFlight::kLongRunning) == 0);
}
