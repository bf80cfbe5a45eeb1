#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "gcode/litho/pass_counts.hpp"

using gcode::litho::pass_range;
using gcode::litho::PassRange;
using gcode::litho::steady_pass_counts;
using gcode::litho::taut_string;

namespace test_pass_counts {

int changes(const std::vector<int>& counts) {
  int n = 0;
  for (std::size_t k = 1; k < counts.size(); ++k) n += counts[k] != counts[k - 1];
  return n;
}

}  // namespace test_pass_counts

TEST_CASE("litho pass counts: the range of a piece is what equal passes within the widths allow", "[litho][pass_counts]") {
  // Widths 0.2 .. 1.0 mm.
  const PassRange a = pass_range(1.22, 2.1, 0.2, 1.0);  // 3 (2.1 / 3 = 0.7) .. 6 (1.22 / 6 = 0.203)
  CHECK(a.fewest == 3);
  CHECK(a.most == 6);
  const PassRange b = pass_range(0.25, 0.25, 0.2, 1.0);  // one pass only
  CHECK(b.fewest == 1);
  CHECK(b.most == 1);
  const PassRange c = pass_range(0, 0.9, 0.2, 1.0);  // a pass begins: the fewest only
  CHECK(c.fewest == 1);
  CHECK(c.most == 1);
  const PassRange none = pass_range(0, 0, 0.2, 1.0);
  CHECK(none.fewest == 0);
  CHECK(none.most == 0);
}

TEST_CASE("litho pass counts: stripes that alternate thin and thick get one count where one fits", "[litho][pass_counts]") {
  // The fewest passes per piece alternate 2, 3, 2, 3 (gaps 1.22 and 2.1 mm):
  // a change at every stripe. Three passes fit both: no change at all.
  std::vector<PassRange> ranges;
  std::vector<double> lengths;
  for (int k = 0; k < 10; ++k) {
    ranges.push_back(k % 2 == 0 ? pass_range(1.22, 1.22, 0.2, 1.0) : pass_range(2.1, 2.1, 0.2, 1.0));
    lengths.push_back(1.0);
  }
  const std::vector<int> counts = steady_pass_counts(ranges, lengths);
  CHECK(test_pass_counts::changes(counts) == 0);
  for (int c : counts) CHECK(c == 3);  // the fewest that fits every piece, not more
}

TEST_CASE("litho pass counts: forced changes stay and the rest keep the fewest passes", "[litho][pass_counts]") {
  // 1 pass only (0.25 mm), then pieces that take 2..5, then 1 only again:
  // two changes whatever is chosen; between them the fewest, 2.
  const std::vector<PassRange> ranges{{1, 1}, {2, 5}, {2, 5}, {1, 1}, {0, 0}, {1, 3}, {2, 3}};
  const std::vector<double> lengths(ranges.size(), 1.0);
  const std::vector<int> counts = steady_pass_counts(ranges, lengths);
  CHECK(counts == std::vector<int>{1, 2, 2, 1, 0, 2, 2});  // {1, 3}: 2 saves the change before {2, 3}
  CHECK(steady_pass_counts({}, {}).empty());
}

TEST_CASE("litho pass counts: the taut string runs straight through a corridor and bends only at its bounds", "[litho][pass_counts]") {
  // A corridor that steps up by 0.04 between x = 2 and x = 3: the string
  // keeps to the lower ceiling, crosses the step in one straight line, and
  // keeps to the higher floor; it never leaves the corridor.
  const std::vector<double> x{0, 1, 2, 2.5, 3, 4, 5};
  const std::vector<double> lo{0.1, 0.1, 0.1, 0.2, 0.55, 0.55, 0.55};
  const std::vector<double> hi{0.51, 0.51, 0.51, 0.8, 0.9, 0.9, 0.9};
  const std::vector<double> y = taut_string(x, lo, hi, 0.51, 0.55);
  for (std::size_t i = 0; i < x.size(); ++i) {
    CHECK(y[i] >= lo[i] - 1e-12);
    CHECK(y[i] <= hi[i] + 1e-12);
  }
  CHECK(y[2] == Approx(0.51));
  CHECK(y[3] == Approx(0.53));  // halfway along the straight crossing
  CHECK(y[4] == Approx(0.55));
  CHECK(y[6] == Approx(0.55));
  // A free corridor: a straight line from first to last.
  const std::vector<double> free = taut_string({0, 1, 3}, {0, 0, 0}, {1, 1, 1}, 0.2, 0.6);
  CHECK(free[1] == Approx(0.3333333333));
  // A point with no room (lo > hi) is held at its middle.
  const std::vector<double> held = taut_string({0, 1, 2}, {0, 0.5, 0}, {1, 0.3, 1}, 0.4, 0.4);
  CHECK(held[1] == Approx(0.4));
}
