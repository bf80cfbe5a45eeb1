#pragma once
// The printer reset mid-print (its greeting came, or after a reconnect its
// line numbers are back at 0): whatever it had queued or planned is lost,
// but the part stands on the bed. Marlin answers a move once it has a
// planner block, so of the moves it acknowledged only the newest
// `planner_blocks` may not have run (fewer when an M400, G28 or G4 was
// acknowledged after them: those answer once every move before them ran).
// The print goes back to the command before the oldest of them: the
// handshake again (M110 N names the last number that went out, so a number
// names one command in the journal), the resume sequence
// (reset_sequence.hpp: heat, declare Z, lift, home X and Y, travel, descend,
// prime, modes), then every command after that one in the print's order.
//
// ResetRecovery decides: which command surely ran, what may print twice,
// the way back to it. The sender (sender_reset.cpp) applies that: it
// renumbers, sends, journals.
#include <array>
#include <cstdint>
#include <vector>

#include "gcode/core/machine_state.hpp"
#include "gcode/serial/protocol/reset_sequence.hpp"

namespace gcode::serial {

// What a reset reads of one command in the sender's history.
struct PrintStep {
  std::uint64_t source_line = 0;
  int layer = 0;
  bool move = false;           // takes a planner block (its ok comes when it has one)
  std::array<double, 3> at{};  // X Y Z after it (what M114 says once it has run)
  bool drains = false;         // M400, G28, G4: its ok comes once every move before it ran
  long long prev = 0;          // the command before it in the print (n - 1 but after a reset)
  long long restore = 0;       // a line of a reset's resume: the command it goes back to
  MachineState after;          // the machine after it
  ResumeTrack track;           // the print up to it
};

// The sender's history as a reset reads it.
class PrintHistory {
 public:
  // Whether command n is in the history (numbered by this sender, not yet
  // overwritten).
  virtual bool holds(long long n) const = 0;
  // Command n of the history (holds(n)).
  virtual const PrintStep& step(long long n) const = 0;
  // Command n: in the history, or the resume's base (ResetRecovery::base).
  virtual const PrintStep& held(long long n) const = 0;
  // The oldest number this sender numbered itself.
  virtual long long first_held() const = 0;

 protected:
  ~PrintHistory() = default;
};

class ResetRecovery {
 public:
  // The command a resume went on after, sent by an earlier gc-send and known
  // from its journal only: surely run, so a reset soon after the resume goes
  // back to it.
  void hold_base(long long n, const MachineState& after, const ResumeTrack& track, std::uint64_t source_line,
                 int layer);
  bool is_base(long long n) const { return n == base_number_; }
  const PrintStep& base() const { return base_; }

  // The newest command that surely ran, walking back from the newest
  // acknowledged one: 0 none (the print starts again), -1 when the way back
  // is no longer held.
  long long surely_ran(const PrintHistory& h, long long last_acked, int planner_blocks) const;
  // Where the printer is to go back to after a reset: surely_ran, or 0
  // when nothing was extruded by then (no part on the bed: the start code
  // homes Z too; only where this sender sent the print from its first
  // line), or -1.
  long long back_to(const PrintHistory& h, long long last_acked, int planner_blocks, long long next_number) const;

  // The acknowledged moves after `back`, which may print twice, and the
  // heights the nozzle may have stopped at.
  struct Redone {
    int moves = 0;
    double mm = 0;
    double z_low = 1e300;
    double z_high = -1e300;
  };
  static Redone may_print_twice(const PrintHistory& h, long long last_acked, long long back);
  // How the way back to command `t` goes (reset_resume_lines makes it).
  static ResetResume way_back(const PrintStep& t, const Redone& redone);
  // The commands given again after the way back, oldest first: every one
  // after `back` in the print's order up to `newest`, but an earlier way
  // back's lines (made anew) and, `final_queued`, the closing M400 (added
  // again).
  static std::vector<long long> given_again(const PrintHistory& h, long long newest, long long back,
                                            bool final_queued);

 private:
  long long base_number_ = -1;  // -1: none
  PrintStep base_;
};

}  // namespace gcode::serial
