#pragma once
// Summary statistics of an error sequence, with the conventions of the TUM benchmark scripts (numpy): the median
// of an even count is the mean of the two middle values, std is the population standard deviation.
#include <cstddef>
#include <limits>
#include <vector>

namespace amos::eval {

struct ErrorStats {
  std::size_t count = 0;
  // All NaN when count == 0.
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double rmse = kNaN, mean = kNaN, median = kNaN, std_dev = kNaN, min = kNaN, max = kNaN;
};

ErrorStats computeErrorStats(const std::vector<double>& values);

// The same statistics with every value multiplied by `factor` (e.g. radians to degrees).
ErrorStats scaled(const ErrorStats& stats, double factor);

}  // namespace amos::eval
