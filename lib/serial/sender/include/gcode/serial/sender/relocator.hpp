#pragma once
// After the port went away and came back (gc-send --reconnect): where the
// printer is. Marlin's "ok" means queued, not done, and answers sent while
// the link was gone were lost, so the sender cannot know which lines the
// printer took; it asks. A line with a number the printer cannot expect is
// refused with "Last Line: n" (every line up to n was taken, and a board
// that kept its power runs them all), then M114 says where it stands, which
// must be where line n left it (printer_report.hpp's axis_off).
//
// The Relocator holds where that stands and decides each step; the sender
// (sender_relink.cpp) sends, fails or goes on as it says.
#include <algorithm>
#include <cstdint>

namespace gcode::serial {

class Relocator {
 public:
  // Down: no port; Probing: the mis-numbered line is out; Locating: the
  // printer named its last line, M114 goes out after the refusal's ok;
  // Finishing: the position is right, M114's own ok is still to come.
  enum class Phase : std::uint8_t { None, Down, Probing, Locating, Finishing };
  enum class Refusal : std::uint8_t {
    Restarted,   // its line numbers are back at 0: a reset like any other
    Impossible,  // a last line before the acknowledged one or past the highest sent
    Took,        // it took every line up to line(): M114 asks where it stands
  };
  enum class Ok : std::uint8_t { AskPosition, Wait, Done };

  Phase phase() const { return phase_; }
  bool active() const { return phase_ != Phase::None; }

  void lost(double now) {
    phase_ = Phase::Down;
    since_ = now;
  }
  // Back on the port: returns the probe's number, which no printer can
  // expect (the highest sent is at most one past its last line).
  long long probe(double now, long long highest_sent);
  // The printer refused the probe and asked for line `expected`: it has
  // every line before it.
  Refusal refused(long long expected, long long last_acked, long long highest_sent, double now);
  // The last line the printer says it took.
  long long line() const { return line_; }
  // Whether a line now may be the answer to M114.
  bool position_due() const { return phase_ == Phase::Locating && position_asked_; }
  // M114's answer put the printer where line() left it.
  void placed() { phase_ = Phase::Finishing; }
  // An "ok" while the printer is located. The first is the refused probe's:
  // the printer's buffer is empty now, M114 goes out (counted by no ledger:
  // its answer is told apart by its text). Until that answer come the oks of
  // lines the printer had queued before the probe (all of them up to its
  // last line, known to be taken); after it, M114's own ok, and sending
  // goes on.
  Ok ok();
  // When the printer, silent since `last_rx`, has not said where it is in time.
  double deadline(double last_rx, double timeout) const { return std::max(since_, last_rx) + timeout; }
  // The link as a restarted printer has it, or the handshake again.
  void forget() {
    phase_ = Phase::None;
    position_asked_ = false;
  }

 private:
  Phase phase_ = Phase::None;
  double since_ = 0;
  long long line_ = 0;
  bool position_asked_ = false;
};

}  // namespace gcode::serial
