#pragma once
// Where a print goes on after a fault, from its journal (journal.hpp) and
// what the printer says about itself (printer_report.hpp).
//
// Marlin's "ok" means "queued", not "done", so which commands ran depends
// on what happened to the printer:
//
//  * It kept running (gc-send was killed, the USB link dropped on a board
//    with its own power, a reconnect without a DTR reset): it drained its
//    queue and planner, so every line up to the one before the line it
//    expects next ran. That line's state must match the printer's reported
//    position within `position_tolerance`; then the print goes on from the
//    next line, exactly.
//  * It reset (its greeting came, or its line numbers are back at zero):
//    whatever was in its queue and planner was lost. A move takes a planner
//    block when it is acknowledged and leaves it when it is done, so of the
//    acknowledged moves only the newest `planner_blocks` may not have run:
//    the print goes on from the oldest of them (some millimetres printed
//    twice, which the plan counts), after a resume sequence that heats,
//    homes X and Y only and sets Z and E from the journal. The lines of an
//    earlier such resume (field restore) go back to where it went.
//  * It kept running, but gc-send had stopped inside such a resume (the
//    last line the printer took is one of it): the resume is made again
//    from where it went back to, Z declared where those lines left the
//    nozzle (once their G92 Z ran, the printer's Z is right), the prime left
//    out when it ran already.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "gcode/core/machine_state.hpp"
#include "gcode/serial/journal/journal.hpp"
#include "gcode/serial/protocol/printer_report.hpp"
#include "gcode/serial/protocol/reset_sequence.hpp"

namespace gcode::serial {

enum class PrinterCondition : std::uint8_t { KeptRunning, Reset };

struct PrinterFindings {
  PrinterCondition condition = PrinterCondition::Reset;
  long long expected_line = -1;          // KeptRunning: the N it expects next
  std::optional<PositionReport> position;  // KeptRunning: its M114 answer
};

struct ResumeLimits {
  int planner_blocks = 16;         // moves a reset may have lost after their "ok"
  double position_tolerance = 0.01;  // mm, journal against M114
  bool can_home_xy_alone = true;   // false: a delta homes all towers at once
};

struct ResumePlan {
  bool possible = false;
  std::string refusal;             // why not (for the user), when !possible
  PrinterCondition condition = PrinterCondition::Reset;
  std::size_t entry = 0;           // the last command taken as run (entries index)
  MachineState state;              // the machine after it
  std::uint64_t input_line = 0;    // go on with the input after this line
  std::uint64_t input_offset = 0;  // ... at this byte
  int layer = 0;
  bool paused = false;             // the print was paused: resume into the pause
  int redone_moves = 0;            // Reset: moves that may print twice
  double redone_mm = 0;            // ... and their length
  ResumeTrack track;               // Reset: the print up to the entry (top, retraction)
  // Reset: the highest Z the nozzle may stand at (it stopped after one of
  // the moves that may print twice); NaN: the state's own Z.
  double nozzle_z = std::numeric_limits<double>::quiet_NaN();
  // Kept running inside an earlier reset's resume: the last line of it the
  // printer took (0: not so), and whether its prime had run.
  std::uint64_t way_back_line = 0;
  bool primed = false;
};

ResumePlan plan_resume(const JournalContents& journal, const PrinterFindings& printer, const ResumeLimits& limits);

}  // namespace gcode::serial
