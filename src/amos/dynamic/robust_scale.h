#pragma once
// The robust statistics the geometric stage takes of track residuals: a median, and the noise scale it implies.
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace amos::dynamic {

// The upper median: the element at index size / 2 once sorted (v must not be empty).
inline double upperMedian(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The noise scale sigma [px] of 2D pixel residuals from their lengths (not empty): for 2D Gaussian noise the median
// length is sqrt(2 ln 2) sigma = 1.1774 sigma. At least 0.1 px, LK's floor on clean images.
inline double pixelNoiseScale(std::vector<double> residual_norms) {
  constexpr double kMedianToSigma = 1.0 / 1.1774;
  constexpr double kMinSigmaPx = 0.1;
  return std::max(kMinSigmaPx, upperMedian(std::move(residual_norms)) * kMedianToSigma);
}

}  // namespace amos::dynamic
