// Where the printer is after its port came back (relocator.hpp): the probe
// numbered two past the highest line sent, the refusal's "Last Line" judged
// against what was acknowledged and sent, M114 asked after the refusal's ok,
// sending going on after M114's own ok.
#include <catch2/catch.hpp>

#include "gcode/serial/sender/relocator.hpp"

using namespace gcode::serial;

namespace test_relocator {

// The port came back at 2 s; N40 is the highest line sent.
Relocator probing() {
  Relocator r;
  r.lost(1);
  r.probe(2, 40);
  return r;
}

}  // namespace test_relocator

TEST_CASE("relocator: the probe is numbered two past the highest line sent", "[serial][reconnect]") {
  Relocator r;
  CHECK_FALSE(r.active());
  r.lost(1);
  CHECK(r.phase() == Relocator::Phase::Down);
  CHECK(r.probe(2, 40) == 42);
  CHECK(r.phase() == Relocator::Phase::Probing);
  // The printer has until the timeout after the probe, or after its last word.
  CHECK(r.deadline(0, 10) == 12);
  CHECK(r.deadline(5, 10) == 15);
}

TEST_CASE("relocator: a last line between the acknowledged and the highest sent is taken, then M114 asks",
          "[serial][reconnect]") {
  Relocator r = test_relocator::probing();
  CHECK(r.refused(38, 30, 40, 3) == Relocator::Refusal::Took);
  CHECK(r.line() == 37);
  CHECK(r.phase() == Relocator::Phase::Locating);
  CHECK_FALSE(r.position_due());
  // The refusal's ok: M114 goes out; the oks of lines queued before the
  // probe wait for its answer.
  CHECK(r.ok() == Relocator::Ok::AskPosition);
  CHECK(r.position_due());
  CHECK(r.ok() == Relocator::Ok::Wait);
  r.placed();
  CHECK(r.phase() == Relocator::Phase::Finishing);
  CHECK(r.ok() == Relocator::Ok::Done);
  CHECK_FALSE(r.active());
}

TEST_CASE("relocator: line numbers back at 0 are a reset, a last line out of range is refused",
          "[serial][reconnect][reset]") {
  Relocator r = test_relocator::probing();
  CHECK(r.refused(1, 30, 40, 3) == Relocator::Refusal::Restarted);
  CHECK(r.refused(30, 30, 40, 3) == Relocator::Refusal::Impossible);  // before the acknowledged N30
  CHECK(r.refused(42, 30, 40, 3) == Relocator::Refusal::Impossible);  // past the highest sent
  CHECK(r.phase() == Relocator::Phase::Probing);
  CHECK(r.refused(41, 30, 40, 3) == Relocator::Refusal::Took);
  r.forget();
  CHECK_FALSE(r.active());
  CHECK_FALSE(r.position_due());
}
