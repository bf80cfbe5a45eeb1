#pragma once
// Whether the printer can still put the file's moves where the file says.
// A printer whose homing failed, or that forgot it while printing (its
// motors were switched off: Klipper's idle timeout, a stepper driver that
// restarted), refuses every move that follows ("!! Must home axis first",
// "echo:Home XYZ First", "Error: G0/G1: insufficient axes homed") and says
// ok to each: streaming on would heat and ooze for hours and end "done".
// The watch reads the answers and says when the print is lost:
//   - an error answering a G28 (firmwares answer a line's error before its
//     ok, so the error answers the oldest line in flight), or one that says
//     a homing failed (protocol.hpp's says_homing_failed: a start macro
//     that homes): the homing failed;
//   - a "not homed" refusal once a G28 was acknowledged: the homing is gone.
// A move refused before any G28 is only a warning: some files move before
// they home, and everything from the G28 on prints.
//
// The sender (sender.hpp) feeds it and stops the print; it decides nothing else.
#include <string>
#include <string_view>

namespace gcode {
class Line;
}

namespace gcode::serial {

// G28 however written ("g28 X Y", "G028 Z"), not G28.1 or G280.
bool is_homing_command(const Line& line);

class HomingWatch {
 public:
  // An error `message` answering `command` (the oldest line in flight; empty
  // when that is none of the file's), `homing` if that is a G28. Returns
  // why the print cannot go on, or nothing.
  std::string error(std::string_view message, std::string_view command, bool homing) const;
  // A message the printer said on its own (an echo).
  std::string message(std::string_view text) const;
  // The printer acknowledged a line, `homing` if a G28.
  void acknowledged(bool homing) { homed_ = homed_ || homing; }
  // The printer restarted: it knows no homing until a G28 again.
  void forget() { homed_ = false; }
  bool homed() const { return homed_; }

 private:
  bool homed_ = false;  // a G28 was acknowledged
};

}  // namespace gcode::serial
