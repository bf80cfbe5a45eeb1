#pragma once
// How many moves go between two pace probes (pacer.hpp) while they tell
// the pacer nothing it did not know. A probe goes when the model says the
// planner is full; one answered as the model said (late: a block ended
// then, or when the model said it ends; Pacer::confirms_model) says the
// model was right, and at the file's pace every probe is: a probe per held
// move, a round trip and a line each (a clean 6000-move print at 1 x sent
// 5392; spaced, 252, and 499 at 2 x, 350 at 10 x).
// Once the first kWarmUp probes have taught the model the printer's pace
// (the floor rises on their answers), each such one in a row doubles the
// moves before the next (0, 1, 3, 7 ... up to kMaxGap), as the model needs
// no check while it holds: a printer slower than the model makes its own
// moves wait (their answers are sightings), and a faster one drains its
// planner a little by each move the model holds back, which the next
// probe finds: one that finds room asks with every held move again (the
// model's pace is wrong). After a command that holds the printer for other
// reasons (a wait, a heating report) the model starts over, and so do the
// probes.
#include <algorithm>

namespace gcode::serial {

class ProbeSpacing {
 public:
  static constexpr long long kMaxGap = 63;   // moves: a probe per 64 at most at the file's pace
  static constexpr long long kWarmUp = 128;  // probes before any is left out (fewer starved a printer twice as fast at the start)

  // May a probe go, `answered` moves answered so far?
  bool due(long long answered) const { return answered >= next_; }
  // A probe answered after `answered` moves; `confirmed`: it came late, as
  // the model said (the planner was full).
  void answered(bool confirmed, long long answered) {
    ++probes_;
    gap_ = confirmed && probes_ > kWarmUp ? std::min(2 * gap_ + 1, kMaxGap) : 0;
    next_ = answered + gap_;
  }
  // The model is not to be trusted as it was: probe with the next held move.
  void reset() {
    gap_ = 0;
    next_ = 0;
  }
  // Moves before the next probe, 0: it goes with the next held move.
  long long gap() const { return gap_; }

 private:
  long long probes_ = 0;  // answered so far
  long long gap_ = 0;     // moves between the last probe and the next
  long long next_ = 0;    // moves answered before the next probe may go
};

}  // namespace gcode::serial
