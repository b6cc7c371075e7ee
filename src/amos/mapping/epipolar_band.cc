#include "amos/mapping/epipolar_band.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace amos::mapping {

EpipolarBand::EpipolarBand(std::vector<BandPoint> points) : points_(std::move(points)) {
  if (points_.empty()) return;
  double u0 = std::numeric_limits<double>::infinity(), v0 = u0;
  for (const BandPoint& p : points_) {
    u0 = std::min(u0, p.u);
    v0 = std::min(v0, p.v);
    max_distance2_ = std::max(max_distance2_, p.max_distance2);
  }
  // Cell of each point (a map, not a grid: keypoints may lie outside the image), then slots grouped by cell.
  std::vector<std::pair<long long, int>> keyed(points_.size());
  for (size_t i = 0; i < points_.size(); ++i) {
    const auto col = static_cast<long long>(std::floor((points_[i].u - u0) / kCellPixels));
    const auto row = static_cast<long long>(std::floor((points_[i].v - v0) / kCellPixels));
    keyed[i] = {row * (1LL << 31) + col, static_cast<int>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  slots_.resize(keyed.size());
  for (size_t k = 0; k < keyed.size();) {
    size_t end = k;
    double min_u = points_[static_cast<size_t>(keyed[k].second)].u, max_u = min_u;
    double min_v = points_[static_cast<size_t>(keyed[k].second)].v, max_v = min_v;
    for (; end < keyed.size() && keyed[end].first == keyed[k].first; ++end) {
      const BandPoint& p = points_[static_cast<size_t>(keyed[end].second)];
      min_u = std::min(min_u, p.u);
      max_u = std::max(max_u, p.u);
      min_v = std::min(min_v, p.v);
      max_v = std::max(max_v, p.v);
      slots_[end] = keyed[end].second;
    }
    cells_.push_back({(min_u + max_u) / 2, (min_v + max_v) / 2, (max_u - min_u) / 2, (max_v - min_v) / 2,
                      static_cast<int>(k), static_cast<int>(end)});
    k = end;
  }
}

void EpipolarBand::near(double a, double b, double c, std::vector<int>& out) const {
  out.clear();
  const double den = a * a + b * b;
  if (den <= 0) return;
  // A point within the widest band has |a u + b v + c| < sqrt(max_distance2 den); over a cell's box the line's
  // value moves by at most |a| half_u + |b| half_v from its value at the centre. The relative margin covers the
  // rounding of these bounds, so the cells skipped hold no point the exact test would keep.
  const double band = std::sqrt(max_distance2_ * den);
  const double abs_a = std::abs(a), abs_b = std::abs(b), abs_c = std::abs(c);
  for (const Cell& cell : cells_) {
    const double reach = band + abs_a * cell.half_u + abs_b * cell.half_v;
    const double scale = abs_a * std::abs(cell.centre_u) + abs_b * std::abs(cell.centre_v) + abs_c + reach;
    if (std::abs(a * cell.centre_u + b * cell.centre_v + c) > reach + 1e-9 * scale) continue;
    for (int k = cell.begin; k < cell.end; ++k) {
      const int slot = slots_[static_cast<size_t>(k)];
      const BandPoint& p = points_[static_cast<size_t>(slot)];
      const double num = a * p.u + b * p.v + c;
      if (!(num * num / den >= p.max_distance2)) out.push_back(slot);
    }
  }
  std::sort(out.begin(), out.end());
}

}  // namespace amos::mapping
