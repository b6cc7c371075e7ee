#include "amos/mapping/epipolar_band.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace amos::mapping {

EpipolarBand::EpipolarBand(std::vector<BandPoint> points) : points_(std::move(points)) {
  for (const BandPoint& p : points_) max_distance2_ = std::max(max_distance2_, p.max_distance2);
  rows_ = makeStrips(points_, true);
  cols_ = makeStrips(points_, false);
}

EpipolarBand::Strips EpipolarBand::makeStrips(const std::vector<BandPoint>& points, bool rows) {
  Strips out;
  if (points.empty()) return out;
  const auto across = [&](const BandPoint& p) { return rows ? p.v : p.u; };
  const auto along = [&](const BandPoint& p) { return rows ? p.u : p.v; };
  double origin = std::numeric_limits<double>::infinity();
  for (const BandPoint& p : points) origin = std::min(origin, across(p));
  // (strip, along, slot): keypoints may lie outside the image, so strips are counted from the smallest one.
  std::vector<std::tuple<long long, double, int>> keyed;
  keyed.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const auto strip = static_cast<long long>(std::floor((across(points[i]) - origin) / kStripPixels));
    keyed.emplace_back(strip, along(points[i]), static_cast<int>(i));
  }
  std::sort(keyed.begin(), keyed.end());
  for (size_t k = 0; k < keyed.size();) {
    Strip strip{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                static_cast<int>(k), 0};
    size_t end = k;
    for (; end < keyed.size() && std::get<0>(keyed[end]) == std::get<0>(keyed[k]); ++end) {
      const int slot = std::get<2>(keyed[end]);
      strip.across_min = std::min(strip.across_min, across(points[static_cast<size_t>(slot)]));
      strip.across_max = std::max(strip.across_max, across(points[static_cast<size_t>(slot)]));
      out.along.push_back(std::get<1>(keyed[end]));
      out.slots.push_back(slot);
    }
    strip.end = static_cast<int>(end);
    out.strips.push_back(strip);
    k = end;
  }
  return out;
}

void EpipolarBand::near(double a, double b, double c, std::vector<int>& out) const {
  out.clear();
  const double den = a * a + b * b;
  if (den <= 0) return;
  if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c)) {
    // No interval to search; the exact test of every point decides (a NaN keeps them all, as the brute force).
    for (size_t i = 0; i < points_.size(); ++i) {
      const double num = a * points_[i].u + b * points_[i].v + c;
      if (!(num * num / den >= points_[i].max_distance2)) out.push_back(static_cast<int>(i));
    }
    return;
  }
  // Walk the strips the line crosses at the steeper angle: there the interval to search in each strip is short.
  if (std::abs(a) >= std::abs(b)) {
    search(rows_, a, b, a, b, c, out);
  } else {
    search(cols_, b, a, a, b, c, out);
  }
  std::sort(out.begin(), out.end());
}

void EpipolarBand::search(const Strips& strips, double along_coef, double across_coef, double a, double b, double c,
                          std::vector<int>& out) const {
  const double den = a * a + b * b;
  // A point the exact test keeps has |along_coef x + across_coef y + c| < sqrt(max_distance2 den), so its x lies
  // within half_width of the line's x at its y. The margin covers the rounding of these bounds (|along_coef| is at
  // least sqrt(den / 2), so nothing here is ill-conditioned).
  const double half_width = std::sqrt(max_distance2_ * den) / std::abs(along_coef);
  for (const Strip& strip : strips.strips) {
    const double x0 = -(across_coef * strip.across_min + c) / along_coef;
    const double x1 = -(across_coef * strip.across_max + c) / along_coef;
    const double margin = 1e-9 * (1 + std::abs(x0) + std::abs(x1) + half_width);
    const double lo = std::min(x0, x1) - half_width - margin, hi = std::max(x0, x1) + half_width + margin;
    const auto first = strips.along.begin() + strip.begin, last = strips.along.begin() + strip.end;
    for (auto it = std::lower_bound(first, last, lo); it != last && *it <= hi; ++it) {
      const int slot = strips.slots[static_cast<size_t>(it - strips.along.begin())];
      const BandPoint& p = points_[static_cast<size_t>(slot)];
      const double num = a * p.u + b * p.v + c;
      if (!(num * num / den >= p.max_distance2)) out.push_back(slot);
    }
  }
}

}  // namespace amos::mapping
