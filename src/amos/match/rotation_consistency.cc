#include "amos/match/rotation_consistency.h"

#include <fmt/format.h>

#include <cmath>

#include "amos/core/error.h"

namespace amos::match {

namespace {
constexpr int kKeptBins = 3;
constexpr double kMinFractionOfBest = 0.1;
}  // namespace

RotationHistogram::RotationHistogram(int num_bins) : num_bins_(num_bins) {
  core::require(num_bins > 0, fmt::format("RotationHistogram needs a positive bin count, got {}", num_bins));
}

int RotationHistogram::binOf(float angle_a_deg, float angle_b_deg) const {
  double rotation = std::fmod(static_cast<double>(angle_a_deg) - angle_b_deg, 360.0);
  if (rotation < 0) rotation += 360.0;
  const int bin = static_cast<int>(std::lround(rotation * num_bins_ / 360.0));
  return bin % num_bins_;  // a rotation just below 360 rounds to num_bins_, which is bin 0
}

void RotationHistogram::add(int id, float angle_a_deg, float angle_b_deg) {
  ids_.push_back(id);
  bins_.push_back(binOf(angle_a_deg, angle_b_deg));
}

std::vector<bool> RotationHistogram::keptBins() const {
  std::vector<int> counts(static_cast<size_t>(num_bins_), 0);
  for (int b : bins_) ++counts[static_cast<size_t>(b)];
  std::vector<bool> kept(static_cast<size_t>(num_bins_), false);
  int best = 0;
  for (int k = 0; k < kKeptBins; ++k) {
    int arg = -1;
    for (int b = 0; b < num_bins_; ++b)
      if (!kept[static_cast<size_t>(b)] && counts[static_cast<size_t>(b)] > 0 &&
          (arg < 0 || counts[static_cast<size_t>(b)] > counts[static_cast<size_t>(arg)]))
        arg = b;
    if (arg < 0) break;
    if (k == 0) best = counts[static_cast<size_t>(arg)];
    if (counts[static_cast<size_t>(arg)] < kMinFractionOfBest * best) break;
    kept[static_cast<size_t>(arg)] = true;
  }
  return kept;
}

std::vector<int> RotationHistogram::consistent() const {
  const std::vector<bool> kept = keptBins();
  std::vector<int> out;
  for (size_t i = 0; i < ids_.size(); ++i)
    if (kept[static_cast<size_t>(bins_[i])]) out.push_back(ids_[i]);
  return out;
}

std::vector<int> RotationHistogram::inconsistent() const {
  const std::vector<bool> kept = keptBins();
  std::vector<int> out;
  for (size_t i = 0; i < ids_.size(); ++i)
    if (!kept[static_cast<size_t>(bins_[i])]) out.push_back(ids_[i]);
  return out;
}

std::vector<bool> rotationConsistent(const std::vector<float>& deltas) {
  RotationHistogram histogram;
  for (std::size_t k = 0; k < deltas.size(); ++k) histogram.add(static_cast<int>(k), deltas[k], 0.0f);
  std::vector<bool> keep(deltas.size(), false);
  for (const int k : histogram.consistent()) keep[k] = true;
  return keep;
}

}  // namespace amos::match
