#pragma once
// The virtual printer's scheduled faults (virtual_printer.hpp): a reset, or a
// link drop after which the printer either runs on or comes back reset, fired
// at a chosen moment so a test can put the fault exactly where it wants it
// (in the start code, mid-layer, at a layer change).
//
// Written as `reset@line=120`, `drop=5@time=30`, `drop-reset=5@layer=3`:
//   reset            the board restarts: queue, planner, position, homing and
//                    heater targets lost, line numbers back to 0, a greeting;
//   drop=S           the USB link is gone for S simulated seconds; the board
//                    keeps its power and executes what it had queued;
//   drop-reset=S     the same, but the board restarts when the link returns
//                    (a board powered over USB);
// and the moment:
//   @line=N          when the command numbered N has been executed;
//   @time=T          at simulated second T;
//   @layer=N         when the first extruding move at the Nth new height has
//                    been executed (layers counted by the printer itself).
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

namespace gcode::serial {

struct ScheduledFault {
  enum class Kind : std::uint8_t { Reset, Drop, DropReset };
  enum class Trigger : std::uint8_t { Line, Time, Layer };
  Kind kind = Kind::Reset;
  double seconds = 0;  // how long a drop lasts
  Trigger trigger = Trigger::Line;
  double at = 0;       // the line number, simulated second or layer
};

// How a restarted board greets: Marlin's "start"; with the NUL a USB-serial
// chip often puts before it; "start" twice (a bootloader's restart);
// "start" then "echo: External Reset" and the firmware line; "start" right
// after the first half of the line the board was sending (the reset cut it).
enum class GreetingForm : std::uint8_t { Start, NulStart, Twice, ExternalReset, CutLine };

// Parses one fault ("drop=5@line=120"). Throws std::invalid_argument naming
// what is wrong.
ScheduledFault parse_scheduled_fault(std::string_view text);
// "start", "nul", "twice", "external", "cut". Throws std::invalid_argument.
GreetingForm parse_greeting_form(std::string_view text);

// The faults still to come, each fired once.
class FaultSchedule {
 public:
  FaultSchedule() = default;
  explicit FaultSchedule(std::vector<ScheduledFault> faults) : faults_(std::move(faults)) {}
  bool empty() const { return faults_.empty(); }
  // A fault due once command `number` has been executed (`started_layer`:
  // the layer it began, 0 for none), taken out of the schedule (false: none).
  bool take_after_command(long long number, int started_layer, ScheduledFault& fault);
  // The earliest @time fault (infinity: none).
  double next_time() const;
  // A time fault due by `now`, taken out of the schedule.
  bool take_due(double now, ScheduledFault& fault);

 private:
  bool take_if(ScheduledFault& fault, bool (*due)(const ScheduledFault&, double, double), double a, double b);
  std::vector<ScheduledFault> faults_;
};

// A link drop while it lasts: down from `t` for some seconds, the board
// restarting when it comes back (drop-reset) or running on (drop).
class LinkOutage {
 public:
  void begin(double t, double seconds, bool reset_after) {
    down_ = true;
    up_at_ = t + seconds;
    reset_after_ = reset_after;
  }
  bool down() const { return down_; }
  // When the link comes back (infinity while it is up).
  double up_at() const { return up_at_; }
  // The link is back: whether the board restarts now.
  bool end() {
    const bool reset = reset_after_;
    *this = LinkOutage();
    return reset;
  }

 private:
  bool down_ = false;
  bool reset_after_ = false;
  double up_at_ = std::numeric_limits<double>::infinity();
};

}  // namespace gcode::serial
