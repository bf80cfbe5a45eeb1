#pragma once
// How many passes side by side each piece of a lithophane layer carries.
// Any count whose equal passes stay within [min pass width, max pass width]
// at both ends of the piece fills it; the passes of neighbouring pieces with
// the same count join into one bead, while a change of count ends every run
// and starts new ones, and each of those ends is a stop of the head. So the
// counts are chosen for the fewest changes along the layer, and among those
// for the fewest passes (the widest beads).
#include <vector>

namespace gcode::litho {

// The counts that fill one piece: fewest (the gap at its wider end within
// max pass width) to most (the gap at its narrower end at least min pass
// width each); most == fewest where nothing else fits or a pass begins or ends.
struct PassRange {
  int fewest = 0;
  int most = 0;
};

// The range of a piece whose gap for passes is g0 and g1 at its ends.
PassRange pass_range(double g0, double g1, double min_pass_width, double max_pass_width);

// One count per piece, each within its range, with the fewest changes from
// one piece to the next; among those, the least of (count - fewest) x length.
std::vector<int> steady_pass_counts(const std::vector<PassRange>& ranges, const std::vector<double>& lengths);

// The taut string through a corridor: y[i] within [lo[i], hi[i]] at x[i]
// (x increasing), from `first` at x[0] to `last` at x[n-1], straight between
// the points where it touches a bound: of all such lines the shortest, so it
// turns as little as the corridor lets it. Where lo > hi the point is fixed
// at (lo + hi) / 2. The passes below the top one follow it (lithophane.cpp).
std::vector<double> taut_string(const std::vector<double>& x, const std::vector<double>& lo,
                                const std::vector<double>& hi, double first, double last);

}  // namespace gcode::litho
