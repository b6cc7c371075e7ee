#include "amos/eval/stats.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace amos::eval {

ErrorStats computeErrorStats(const std::vector<double>& values) {
  ErrorStats s;
  s.count = values.size();
  if (values.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    s.rmse = s.mean = s.median = s.std_dev = s.min = s.max = nan;
    return s;
  }
  const double n = static_cast<double>(values.size());
  double sum = 0, sum_sq = 0;
  for (double v : values) {
    sum += v;
    sum_sq += v * v;
  }
  s.rmse = std::sqrt(sum_sq / n);
  s.mean = sum / n;
  double centred_sq = 0;  // two-pass variance, as numpy.std does
  for (double v : values) centred_sq += (v - s.mean) * (v - s.mean);
  s.std_dev = std::sqrt(centred_sq / n);
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t mid = sorted.size() / 2;
  s.median = sorted.size() % 2 == 1 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
  s.min = sorted.front();
  s.max = sorted.back();
  return s;
}

ErrorStats scaled(const ErrorStats& stats, double factor) {
  ErrorStats s = stats;
  for (double* v : {&s.rmse, &s.mean, &s.median, &s.std_dev, &s.min, &s.max}) *v *= factor;
  return s;
}

}  // namespace amos::eval
