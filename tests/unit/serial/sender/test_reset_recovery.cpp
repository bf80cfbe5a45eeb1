// What a reset goes back to (reset_recovery.hpp), on a history written by
// hand: the newest `planner_blocks` acknowledged moves may not have run, an
// acknowledged drain did, a resume's base did; the moves after the command
// that surely ran may print twice; the way back and what is given again.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>

#include "gcode/serial/sender/reset_recovery.hpp"

using namespace gcode::serial;

namespace test_reset_recovery {

// Commands first..last, each after the one before; moves along X, 1 mm each.
class History : public PrintHistory {
 public:
  History(long long first, long long last) : first_(first), last_(last) {
    for (long long n = first; n <= last; ++n) {
      PrintStep& s = steps_[n];
      s.source_line = static_cast<std::uint64_t>(n);
      s.move = true;
      s.prev = n - 1;
      s.at = {static_cast<double>(n), 0, 0.2};
      s.after.position = {static_cast<double>(n), 0, 0.2, 0};
      s.track.top_z = 0.2;
    }
  }
  PrintStep& at(long long n) { return steps_[n]; }
  bool holds(long long n) const override { return n >= first_ && n <= last_; }
  const PrintStep& step(long long n) const override { return steps_.at(n); }
  const PrintStep& held(long long n) const override {
    return recovery != nullptr && recovery->is_base(n) ? recovery->base() : steps_.at(n);
  }
  long long first_held() const override { return first_; }
  const ResetRecovery* recovery = nullptr;

 private:
  long long first_, last_;
  std::map<long long, PrintStep> steps_;
};

}  // namespace test_reset_recovery

using test_reset_recovery::History;

TEST_CASE("reset recovery: the newest planner_blocks acknowledged moves may not have run", "[serial][reset]") {
  History h(1, 40);
  ResetRecovery r;
  CHECK(r.surely_ran(h, 40, 16) == 24);
  CHECK(r.back_to(h, 40, 16, 41) == 24);
  // An acknowledged M400 answered once every move before it ran.
  h.at(30).move = false;
  h.at(30).drains = true;
  CHECK(r.surely_ran(h, 40, 16) == 30);
  // Fewer acknowledged moves than the planner holds: back to the start.
  History few(1, 10);
  CHECK(r.surely_ran(few, 10, 16) == 0);
  CHECK(r.back_to(few, 10, 16, 11) == 0);
}

TEST_CASE("reset recovery: a resume's base surely ran, what is older is not held", "[serial][reset][resume]") {
  History h(41, 50);  // a resume that went on after command 40
  ResetRecovery r;
  h.recovery = &r;
  CHECK(r.surely_ran(h, 50, 16) == -1);
  r.hold_base(40, h.at(41).after, h.at(41).track, 120, 2);
  CHECK(r.is_base(40));
  CHECK(r.base().drains);
  CHECK(r.surely_ran(h, 50, 16) == 40);
  CHECK(r.back_to(h, 50, 16, 51) == 40);
  // Nothing extruded by then, not from the first line: no way back.
  History bare(41, 50);
  ResetRecovery none;
  bare.recovery = &none;
  none.hold_base(40, gcode::MachineState{}, ResumeTrack{}, 120, 2);
  CHECK(none.surely_ran(bare, 50, 16) == 40);
  CHECK(none.back_to(bare, 50, 16, 51) == -1);
}

TEST_CASE("reset recovery: a line of an earlier way back goes back where that one did", "[serial][reset]") {
  History h(1, 40);
  ResetRecovery r;
  h.at(38).restore = 20;
  CHECK(r.surely_ran(h, 40, 16) == 20);
}

TEST_CASE("reset recovery: the moves after the way back's target may print twice", "[serial][reset]") {
  History h(1, 40);
  h.at(40).after.position[gcode::kZ] = 0.4;
  const ResetRecovery::Redone redone = ResetRecovery::may_print_twice(h, 40, 24);
  CHECK(redone.moves == 16);
  CHECK(redone.mm == Approx(16));
  CHECK(redone.z_low == Approx(0.2));
  CHECK(redone.z_high == Approx(0.4));
  // The nozzle is taken to stand at the highest of them.
  const ResetResume way = ResetRecovery::way_back(h.at(24), redone);
  CHECK(way.nozzle_z == Approx(0.4));
  CHECK(way.top_z == Approx(0.2));
  // All at the target's height: the nozzle is where the target left it.
  const ResetResume level = ResetRecovery::way_back(h.at(24), ResetRecovery::may_print_twice(h, 39, 24));
  CHECK(std::isnan(level.nozzle_z));
}

TEST_CASE("reset recovery: inside a block of gc-send's own the way back primes nothing of the print's",
          "[serial][reset]") {
  History h(1, 40);
  h.at(24).track.retracted = h.at(24).track.retraction = 0.8;
  const ResetRecovery::Redone redone = ResetRecovery::may_print_twice(h, 40, 24);
  CHECK(ResetRecovery::way_back(h.at(24), redone).prime == Approx(0.8));
  h.at(24).source_line = 0;
  const ResetResume own = ResetRecovery::way_back(h.at(24), redone);
  CHECK(own.prime == 0);
  CHECK(own.retracted == 0);
}

TEST_CASE("reset recovery: given again after the way back, in order, without an earlier way back or the final M400",
          "[serial][reset]") {
  History h(1, 30);
  h.at(27).restore = 10;
  h.at(30).source_line = 0;  // the closing M400
  CHECK(ResetRecovery::given_again(h, 30, 24, false) == std::vector<long long>{25, 26, 28, 29, 30});
  CHECK(ResetRecovery::given_again(h, 30, 24, true) == std::vector<long long>{25, 26, 28, 29});
  CHECK(ResetRecovery::given_again(h, 30, 0, true).size() == 28);
}
