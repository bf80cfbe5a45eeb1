#pragma once
// The sender's resend state machine. "Resend: n" rewinds to line n. Marlin
// empties its receive buffer after a bad line, and every line still on the
// wire then fails too and asks for the same n again (each with its own
// "ok"), and each of those empties the buffer again, taking any early copy
// of line n with it. Stale lines wait in the buffer while a move blocks on
// a full planner, so silence alone proves nothing. After a rewind the sender
// therefore settles: it waits until every line before n is acknowledged
// (the queue is empty, so the firmware reads each arriving line at once)
// and the link has then been quiet for a few byte times; repeated requests
// for n meanwhile are ignored, and only then does line n go again. The "ok"
// after each Resend belongs to the rejected line and frees nothing.
#include <algorithm>
#include <cstdint>

namespace gcode::serial {

class ResendState {
 public:
  enum class Verdict : std::uint8_t {
    Rewind,   // go back to the line asked for
    Repeat,   // a stale line's request for the line being resent: ignored
    TooMany,  // asked for the same line more than max_resends times in a row
  };
  // A request for line `n`, which was sent and is still in the history.
  Verdict request(long long n, int max_resends);
  // The sender went back to line `n`: it settles for `quiet` seconds of
  // silence from `now` on.
  void rewound(long long n, double now, double quiet) {
    settling_ = true;
    line_ = n;
    from_ = now;
    quiet_ = quiet;
  }
  bool settling() const { return settling_; }
  // Something was written or heard: the quiet starts again.
  void heard(double now) {
    if (settling_) from_ = std::max(from_, now);
  }
  // When the link has been quiet long enough, the last byte received at `last_rx`.
  double quiet_at(double last_rx) const { return std::max(from_, last_rx) + quiet_; }
  bool quiet(double now, double last_rx) const { return now >= from_ + quiet_ && now >= last_rx + quiet_; }
  void settled() { settling_ = false; }
  int count() const { return count_; }

  // The "ok" of a rejected line comes right after its "Resend:"; anything
  // else in between means that ok was lost (or the firmware sends none).
  void expect_rejected_ok() { expect_ok_ = true; }
  void other_answer() { expect_ok_ = false; }
  // Whether this "ok" is the rejected line's (it frees nothing).
  bool take_rejected_ok() {
    bool was = expect_ok_;
    expect_ok_ = false;
    return was;
  }

 private:
  bool settling_ = false;
  long long line_ = -1;     // the line being resent
  double from_ = 0;         // the quiet counts from here
  double quiet_ = 0;
  long long asked_ = -1;    // the line asked for last
  int count_ = 0;           // requests for it in a row
  bool expect_ok_ = false;
};

}  // namespace gcode::serial
