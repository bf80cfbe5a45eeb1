// The take-back ledger (gcode/serial/control/take_back.hpp): what the
// sender has sent (all but the newest it holds unsent) can no longer be taken back, nor anything over lines of
// gc-send's own; what is taken back comes oldest first.
#include <catch2/catch.hpp>

#include <cstdint>

#include "gcode/serial/control/take_back.hpp"

using gcode::serial::TakeBackLedger;

namespace test_take_back {

TakeBackLedger::Entry command(long long number, std::uint64_t source) {
  TakeBackLedger::Entry e;
  e.number = number;
  e.source = source;
  return e;
}

}  // namespace test_take_back

TEST_CASE("take back: only the newest unsent commands, oldest first", "[serial][take_back]") {
  TakeBackLedger ledger;
  for (int i = 1; i <= 3; ++i) ledger.handed(test_take_back::command(i, 10 + i));
  CHECK(ledger.size() == 3);
  ledger.keep_unsent(2);  // the sender holds two unsent: command 1 went out, no longer takeable
  CHECK(ledger.size() == 2);
  CHECK(ledger.can_take_back(2, 2));
  CHECK_FALSE(ledger.can_take_back(2, 1));  // the sender holds only one unsent
  CHECK_FALSE(ledger.can_take_back(3, 5));  // only two are in the ledger
  CHECK_FALSE(ledger.can_take_back(0, 2));
  auto back = ledger.take_back(2);
  REQUIRE(back.size() == 2);
  CHECK(back[0].source == 12);
  CHECK(back[1].source == 13);
  CHECK(ledger.size() == 0);
  CHECK(ledger.last_source() == 11);  // the sent one stays handed over
}

TEST_CASE("take back: lines of gc-send's own close the ledger", "[serial][take_back]") {
  TakeBackLedger ledger;
  ledger.handed(test_take_back::command(1, 5));
  ledger.handed(test_take_back::command(2, 6));
  ledger.own_lines(6);
  CHECK(ledger.size() == 0);
  CHECK_FALSE(ledger.can_take_back(1, 4));
  CHECK(ledger.last_source() == 6);
}
