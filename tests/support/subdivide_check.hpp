#pragma once
// The independent checker for gc-subdivide: replays the input and the output
// through MachineState side by side and proves, line by line of the input,
//   (a) every output piece lies on its original move (<= 0.001 mm off; for
//       arcs: on the circle),
//   (b) the filament of the pieces of a move sums to the move's (<= 1e-5 mm),
//   (c) position, E, F and modes are equal after every input line,
//   (d) no output move is longer than the limit (or shorter than the minimum,
//       but for the last piece of a move; 0.002 mm of rounding allowed),
//   (e) every other line is byte-identical and in the same order.
// It knows the limit only from the documented formula, not from the library.
#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace gctest {

struct SubdivideLimits {
  double max = 0;        // --max
  double latency = 0;    // --latency
  double buffer = 20;    // --buffer
  double rate = 0;       // --max-rate
  double min = 0.05;     // --min
  bool travel = true;    // --travel / --no-travel
  bool arcs = true;      // --arcs split
  // Per input line (0-based): whether splitting applies there; empty = everywhere.
  std::vector<bool> selected;

  // The documented rule: --max, or speed x latency / buffer floored at twice
  // --min; then at least speed / max-rate.
  double limit(double feedrate) const {
    double l = 0;
    if (max > 0) {
      l = max;
    } else if (latency > 0 && feedrate > 0) {
      l = std::max(feedrate / 60 * latency / buffer, 2 * min);
    }
    if (l > 0 && rate > 0 && feedrate > 0) l = std::max(l, feedrate / 60 / rate);
    return l;
  }
};

struct SubdivideCheck {
  std::size_t moves_split = 0;
  std::size_t pieces = 0;
  std::size_t arcs = 0;
  std::vector<std::string> failures;  // empty: every invariant holds
  bool ok() const { return failures.empty(); }
  std::string first_failure() const { return failures.empty() ? std::string() : failures.front(); }
};

// Checks gc-subdivide's `output` of `input` under `limits` (subdivide_check.cpp).
SubdivideCheck check_subdivision(std::string_view input, std::string_view output, const SubdivideLimits& limits);

}  // namespace gctest
