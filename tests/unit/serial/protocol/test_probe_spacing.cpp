// The moves between two pace probes (gcode/serial/protocol/probe_spacing.hpp):
// none while the model learns the printer (the first kWarmUp probes), then
// doubling with each probe the printer answers late as the model said, up
// to kMaxGap; none again after one that finds room, or after a reset.
#include <catch2/catch.hpp>

#include <algorithm>

#include "gcode/serial/protocol/probe_spacing.hpp"

using gcode::serial::ProbeSpacing;

namespace test_probe_spacing {

// `n` probes answered late, one per move answered, from move `from` on.
long long confirm(ProbeSpacing& s, int n, long long from) {
  long long answered = from;
  for (int i = 0; i < n; ++i) {
    answered += s.gap() + 1;
    REQUIRE(s.due(answered));
    s.answered(true, answered);
  }
  return answered;
}

}  // namespace test_probe_spacing

using test_probe_spacing::confirm;

TEST_CASE("probe spacing: every held move is probed while the model learns, then the gap doubles up to its limit",
          "[serial][probe_spacing]") {
  ProbeSpacing s;
  CHECK(s.due(0));
  long long answered = confirm(s, static_cast<int>(ProbeSpacing::kWarmUp), 0);
  CHECK(s.gap() == 0);  // still learning: each late probe leaves the next move probed
  CHECK(s.due(answered));
  long long expected = 0;
  for (int i = 0; i < 10; ++i) {
    answered = confirm(s, 1, answered);
    expected = std::min(2 * expected + 1, ProbeSpacing::kMaxGap);
    CHECK(s.gap() == expected);
    // The next probe waits for that many more moves' answers.
    CHECK_FALSE(s.due(answered + s.gap() - 1));
    CHECK(s.due(answered + s.gap()));
  }
  CHECK(s.gap() == ProbeSpacing::kMaxGap);
}

TEST_CASE("probe spacing: a probe that finds room, or a reset, probes the next held move again",
          "[serial][probe_spacing]") {
  ProbeSpacing s;
  long long answered = confirm(s, static_cast<int>(ProbeSpacing::kWarmUp) + 4, 0);
  REQUIRE(s.gap() == 15);
  answered += s.gap() + 1;
  s.answered(false, answered);  // room: the model's pace was wrong
  CHECK(s.gap() == 0);
  CHECK(s.due(answered));
  answered = confirm(s, 3, answered);
  REQUIRE(s.gap() == 7);
  CHECK_FALSE(s.due(answered));
  s.reset();  // a wait or a heating report: the model starts over
  CHECK(s.gap() == 0);
  CHECK(s.due(answered));
}
