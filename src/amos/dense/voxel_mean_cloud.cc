#include "amos/dense/voxel_mean_cloud.h"

#include <algorithm>
#include <cmath>

#include "amos/core/error.h"

namespace amos::dense {
namespace {

// 21 bits per axis: +-2^20 voxels, +-21 km at 2 cm, beyond any room or walk a depth camera maps.
std::uint64_t packedKey(const Eigen::Vector3d& scaled) {
  constexpr std::int64_t kOffset = std::int64_t{1} << 20, kMask = (std::int64_t{1} << 21) - 1;
  std::uint64_t key = 0;
  for (int i = 0; i < 3; ++i) {
    const std::int64_t cell = static_cast<std::int64_t>(std::floor(scaled[i])) + kOffset;
    key = (key << 21) | static_cast<std::uint64_t>(std::clamp<std::int64_t>(cell, 0, kMask));
  }
  return key;
}

}  // namespace

VoxelMeanCloud::VoxelMeanCloud(double voxel) : inverse_voxel_(1.0 / voxel) {
  core::require(std::isfinite(voxel) && voxel > 0, "VoxelMeanCloud: the voxel must be > 0 m");
}

void VoxelMeanCloud::add(const Eigen::Vector3d& point, const Eigen::Vector3d& colour) {
  const auto [at, inserted] = index_.try_emplace(packedKey(point * inverse_voxel_), sums_.size());
  if (inserted) sums_.emplace_back();
  Sum& sum = sums_[at->second];
  sum.point += point;
  sum.colour += colour;
  ++sum.count;
}

DenseCloud VoxelMeanCloud::cloud() const {
  DenseCloud out;
  out.points.reserve(sums_.size());
  out.colours.reserve(sums_.size());
  for (const Sum& sum : sums_) {
    const double n = static_cast<double>(sum.count);
    out.points.push_back(sum.point / n);
    Rgb rgb;
    for (int i = 0; i < 3; ++i)
      rgb[i] = static_cast<std::uint8_t>(std::round(std::clamp(sum.colour[i] / n, 0.0, 1.0) * 255.0));
    out.colours.push_back(rgb);
  }
  return out;
}

}  // namespace amos::dense
