// The speed factor the pacer learns (gcode/serial/protocol/pace_rate.hpp):
// a floor raises it at once, samples only lower it, within its bounds.
#include <catch2/catch.hpp>

#include "gcode/serial/protocol/pace_rate.hpp"

using gcode::serial::PaceRate;

TEST_CASE("pace rate: the floor raises at once, samples only lower", "[serial][pace_rate]") {
  PaceRate rate;
  CHECK(rate.factor() == 1);
  rate.at_least(4);
  CHECK(rate.factor() == 4);
  rate.sample(2, PaceRate::kSpan);  // a full span replaces the estimate
  CHECK(rate.factor() == Approx(2));
  rate.sample(8, PaceRate::kSpan);  // never up by timing
  CHECK(rate.factor() == Approx(2));
  rate.sample(1, PaceRate::kSpan / 2);  // half a span: half way, geometrically
  CHECK(rate.factor() == Approx(1.41421).epsilon(1e-4));
  rate.sample(0, 10);  // no evidence
  CHECK(rate.factor() == Approx(1.41421).epsilon(1e-4));
  rate.at_least(1000);
  CHECK(rate.factor() == PaceRate::kMax);
  rate.sample(0.1, PaceRate::kSpan);
  CHECK(rate.factor() == PaceRate::kMin);
}
