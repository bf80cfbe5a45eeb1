#pragma once
// When the sender asks again (M105) for an answer that is overdue: at most
// kQuick such questions in a row, each waiting twice as long as the one
// before; after that only the timeout asks. Any real answer starts over.
#include <algorithm>

namespace gcode::serial {

class ProbeBackoff {
 public:
  static constexpr int kQuick = 3;

  // An answer came: the next question may go as soon as one is overdue.
  void answered() {
    in_row_ = 0;
    next_ = 0;
  }
  // A question was due at `now` (asked, or left out for want of room).
  void asked(double now, double margin) {
    ++in_row_;
    next_ = now + margin * factor(in_row_);
  }
  // Another quick question may go.
  bool quick() const { return in_row_ < kQuick; }
  // When the question about an answer due at `due` goes.
  double when(double due, double margin) const { return std::max(due + margin * (factor(in_row_) - 1), next_); }

 private:
  static double factor(int k) { return static_cast<double>(1 << std::min(k, 10)); }

  int in_row_ = 0;     // questions without an answer
  double next_ = 0;    // no question before this
};

}  // namespace gcode::serial
