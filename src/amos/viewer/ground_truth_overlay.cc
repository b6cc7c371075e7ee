#include "amos/viewer/ground_truth_overlay.h"

#include "amos/core/error.h"
#include "amos/eval/ate.h"

namespace amos::viewer {

std::vector<TrajectoryPoint> groundTruthInMapFrame(const std::vector<io::StampedPose>& ground_truth,
                                                   const eval::Alignment& alignment) {
  const Eigen::Matrix3d R_inv = alignment.transform.linear().transpose();
  const Eigen::Vector3d t = alignment.transform.translation();
  std::vector<TrajectoryPoint> out;
  out.reserve(ground_truth.size());
  for (const io::StampedPose& p : ground_truth) {
    const Eigen::Vector3d in_map = R_inv * (p.T_wc.translation() - t) / alignment.scale;
    out.push_back({p.timestamp, in_map.cast<float>()});
  }
  return out;
}

std::optional<eval::Alignment> alignEstimate(const std::vector<io::StampedPose>& ground_truth,
                                             const std::vector<io::StampedPose>& estimate) {
  if (ground_truth.empty() || estimate.size() < 3) return std::nullopt;
  try {
    const eval::AteResult ate = eval::computeAte(ground_truth, estimate);
    if (ate.errors_m.size() < 3) return std::nullopt;
    return ate.alignment;
  } catch (const core::Error&) {
    return std::nullopt;
  }
}

}  // namespace amos::viewer
