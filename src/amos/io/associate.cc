#include "amos/io/associate.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "amos/core/error.h"

namespace amos::io {

std::vector<std::pair<std::size_t, std::size_t>> associateStamps(const std::vector<double>& first,
                                                                 const std::vector<double>& second,
                                                                 double max_difference, double offset) {
  core::require(max_difference > 0, "association: max_difference must be positive");
  auto sortedOrder = [](const std::vector<double>& stamps) {
    std::vector<std::size_t> order(stamps.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return stamps[x] < stamps[y]; });
    return order;
  };
  const std::vector<std::size_t> order_a = sortedOrder(first);
  const std::vector<std::size_t> order_b = sortedOrder(second);
  std::vector<double> shifted_b(order_b.size());  // b + offset in sorted order, still monotone
  for (std::size_t k = 0; k < order_b.size(); ++k) shifted_b[k] = second[order_b[k]] + offset;

  // Candidate generation: for each a only the b whose shifted stamp lies in a window around a; the window is
  // wider than max_difference and the exact predicate of associate.py decides.
  struct Candidate {
    double diff;
    std::size_t a, b;  // positions in the sorted orders, so ties order by stamp value as in Python
  };
  std::vector<Candidate> candidates;
  const double window = 2.0 * max_difference;
  std::size_t lo = 0;
  for (std::size_t ka = 0; ka < order_a.size(); ++ka) {
    const double a = first[order_a[ka]];
    while (lo < shifted_b.size() && shifted_b[lo] < a - window) ++lo;
    for (std::size_t kb = lo; kb < shifted_b.size() && shifted_b[kb] <= a + window; ++kb) {
      const double diff = std::abs(a - shifted_b[kb]);
      if (diff < max_difference) candidates.push_back({diff, ka, kb});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.diff, x.a, x.b) < std::tie(y.diff, y.a, y.b);
  });

  std::vector<bool> used_a(order_a.size(), false), used_b(order_b.size(), false);
  std::vector<std::pair<std::size_t, std::size_t>> sorted_matches;
  for (const Candidate& c : candidates) {
    if (used_a[c.a] || used_b[c.b]) continue;
    used_a[c.a] = used_b[c.b] = true;
    sorted_matches.emplace_back(c.a, c.b);
  }
  std::sort(sorted_matches.begin(), sorted_matches.end());
  std::vector<std::pair<std::size_t, std::size_t>> matches;
  matches.reserve(sorted_matches.size());
  for (const auto& [ka, kb] : sorted_matches) matches.emplace_back(order_a[ka], order_b[kb]);
  return matches;
}

}  // namespace amos::io
