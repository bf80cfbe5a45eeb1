#include "gcode/litho/pass_counts.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace gcode::litho {

PassRange pass_range(double g0, double g1, double min_pass_width, double max_pass_width) {
  const double wide = std::max(g0, g1);
  const double narrow = std::min(g0, g1);
  if (!(wide > 0)) return {0, 0};
  const int fewest = std::max(1, static_cast<int>(std::ceil(wide / max_pass_width - 1e-9)));
  // A piece where a pass begins or ends (one end has no gap) keeps the fewest.
  if (!(narrow > 0)) return {fewest, fewest};
  const int most = static_cast<int>(std::floor(narrow / min_pass_width + 1e-9));
  return {fewest, std::max(fewest, most)};
}

// Dynamic programming over the pieces: for each piece and each count in its
// range, the best (changes, extra pass length) of the pieces up to it ending
// in that count; then back from the best last count.
std::vector<int> steady_pass_counts(const std::vector<PassRange>& ranges, const std::vector<double>& lengths) {
  const std::size_t m = ranges.size();
  std::vector<int> counts(m, 0);
  if (m == 0) return counts;
  struct Cost {
    int changes = 0;
    double extra = 0;
    bool operator<(const Cost& o) const { return changes != o.changes ? changes < o.changes : extra < o.extra - 1e-12; }
  };
  std::vector<std::vector<Cost>> best(m);
  std::vector<std::vector<int>> from(m);  // the previous piece's count behind each best
  for (std::size_t k = 0; k < m; ++k) {
    const PassRange r = ranges[k];
    const std::size_t n = static_cast<std::size_t>(r.most - r.fewest + 1);
    best[k].assign(n, Cost{});
    from[k].assign(n, 0);
    for (std::size_t c = 0; c < n; ++c) {
      const int count = r.fewest + static_cast<int>(c);
      const double extra = (count - r.fewest) * lengths[k];
      if (k == 0) {
        best[k][c] = {0, extra};
        continue;
      }
      const PassRange p = ranges[k - 1];
      Cost top{std::numeric_limits<int>::max(), 0};
      for (int before = p.fewest; before <= p.most; ++before) {
        Cost cost = best[k - 1][static_cast<std::size_t>(before - p.fewest)];
        cost.changes += before != count;
        cost.extra += extra;
        if (cost < top) {
          top = cost;
          from[k][c] = before;
        }
      }
      best[k][c] = top;
    }
  }
  const auto last = std::min_element(best[m - 1].begin(), best[m - 1].end());
  int count = ranges[m - 1].fewest + static_cast<int>(last - best[m - 1].begin());
  for (std::size_t k = m; k-- > 0;) {
    counts[k] = count;
    if (k > 0) count = from[k][static_cast<std::size_t>(count - ranges[k].fewest)];
  }
  return counts;
}

// String pulling: from the last corner (the apex) the slopes that clear
// every bound so far form a window; a bound that closes the window bends
// the string at the point that set the window's other side, which becomes
// the next apex. Between corners the string is straight.
std::vector<double> taut_string(const std::vector<double>& x, const std::vector<double>& lo,
                                const std::vector<double>& hi, double first, double last) {
  const std::size_t n = x.size();
  std::vector<double> y(n, first);
  if (n < 2) return y;
  auto low = [&](std::size_t i) {
    if (i == n - 1) return last;
    return lo[i] <= hi[i] ? lo[i] : (lo[i] + hi[i]) / 2;
  };
  auto high = [&](std::size_t i) {
    if (i == n - 1) return last;
    return lo[i] <= hi[i] ? hi[i] : (lo[i] + hi[i]) / 2;
  };
  std::size_t apex = 0;
  double ya = first;
  while (apex < n - 1) {
    double smin = -std::numeric_limits<double>::infinity(), smax = std::numeric_limits<double>::infinity();
    std::size_t at_min = apex + 1, at_max = apex + 1;
    std::size_t next = n - 1;  // the next corner
    double y_next = last;
    for (std::size_t j = apex + 1; j < n; ++j) {
      const double dx = x[j] - x[apex];
      const double s_lo = (low(j) - ya) / dx, s_hi = (high(j) - ya) / dx;
      if (s_lo > smax) {  // the string goes over the ceiling's point
        next = at_max;
        y_next = high(at_max);
        break;
      }
      if (s_hi < smin) {  // the string goes under the floor's point
        next = at_min;
        y_next = low(at_min);
        break;
      }
      if (s_lo >= smin) {
        smin = s_lo;
        at_min = j;
      }
      if (s_hi <= smax) {
        smax = s_hi;
        at_max = j;
      }
    }
    for (std::size_t i = apex + 1; i <= next; ++i)
      y[i] = ya + (y_next - ya) * (x[i] - x[apex]) / (x[next] - x[apex]);
    y[next] = y_next;
    apex = next;
    ya = y_next;
  }
  return y;
}

}  // namespace gcode::litho
