// Back into a pause after gc-send --resume (gcode/serial/control/pause_reentry.hpp):
// the rest of a block half run goes out when the printer stands where its
// first lines leave it; otherwise, or when the block ran whole, the head
// waits where it stands and the way back starts from there.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/serial/control/pause_reentry.hpp"
#include "gcode/transform/pause_sequence.hpp"
#include "test_support.hpp"

using namespace gcode;
using namespace gcode::serial;

namespace test_pause_reentry {

MachineState stopped_at() {
  return gctest::replay_state("G28\nM104 S205\nM82\nG1 X10 Y20 Z0.3 F1500\nG1 X20 E5.12345\n");
}

PauseConfig park_at(double x, double y) {
  PauseConfig c;
  c.park = true;
  c.park_x = x;
  c.park_y = y;
  return c;
}

MachineState after(MachineState s, const std::vector<std::string>& lines, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) s.apply(Line::parse(lines[i]));
  return s;
}

}  // namespace test_pause_reentry

using namespace test_pause_reentry;

TEST_CASE("pause reentry: a block half run goes on from where the printer stands", "[serial][pause_reentry]") {
  const MachineState at = stopped_at();
  const PauseBlock block = build_pause(PausePoint{at}, park_at(110, 210));
  REQUIRE(block.pause.size() > 3);
  const MachineState printer = after(at, block.pause, 2);
  PauseReentry reentry(at, 0, 0, nullptr, printer, 2);
  REQUIRE(reentry.finish_block(park_at(110, 210)));
  CHECK(reentry.warning().empty());
  CHECK(reentry.block_lines() == block.pause.size());
  CHECK(reentry.rest() == std::vector<std::string>(block.pause.begin() + 2, block.pause.end()));
  CHECK(reentry.resume_lines() == block.resume);
  const MachineState end = after(at, block.pause, block.pause.size());
  CHECK(reentry.resume_from().position[kX] == end.position[kX]);
  CHECK(reentry.resume_from().position[kY] == end.position[kY]);
  CHECK(reentry.resume_from().position[kZ] == end.position[kZ]);
}

TEST_CASE("pause reentry: options that make another block leave the head where it stands",
          "[serial][pause_reentry]") {
  const MachineState at = stopped_at();
  const PauseBlock block = build_pause(PausePoint{at}, park_at(110, 210));
  // The printer took all but the last line of a block parked elsewhere.
  const std::vector<std::string> other = build_pause(PausePoint{at}, park_at(50, 60)).pause;
  const MachineState printer = after(at, other, other.size() - 1);
  PauseReentry reentry(at, 0, 0, nullptr, printer, other.size() - 1);
  CHECK_FALSE(reentry.finish_block(park_at(110, 210)));
  CHECK(reentry.warning().find("do not make") != std::string::npos);
  reentry.park_here(park_at(110, 210));
  CHECK(reentry.rest().empty());
  // The way back of a block parked where the printer stands, from the stop.
  const PauseBlock here = build_pause(PausePoint{at}, park_at(printer.position[kX], printer.position[kY]));
  CHECK(reentry.resume_lines() == here.resume);
  CHECK(reentry.resume_from().position[kX] == printer.position[kX]);
  CHECK(block.pause.size() == here.pause.size());
}

TEST_CASE("pause reentry: a block that ran whole, or cannot be made again", "[serial][pause_reentry]") {
  const MachineState at = stopped_at();
  const PauseBlock block = build_pause(PausePoint{at}, park_at(110, 210));
  const MachineState parked = after(at, block.pause, block.pause.size());
  PauseReentry whole(at, 0, 0, nullptr, parked, block.pause.size());
  CHECK_FALSE(whole.finish_block(park_at(110, 210)));
  CHECK(whole.warning().empty());  // nothing to finish, nothing to say
  PauseReentry none_ran(at, 0, 0, nullptr, at, 0);
  none_ran.cannot_make("no bed");
  CHECK(none_ran.warning().empty());
  PauseReentry half(at, 0, 0, nullptr, at, 2);
  half.cannot_make("no bed");
  CHECK(half.warning().find("cannot make again (no bed)") != std::string::npos);
}
