#include "amos/eval/ate.h"

#include <fmt/format.h>

#include "amos/core/error.h"

namespace amos::eval {

AteResult computeAte(const std::vector<io::StampedPose>& gt_raw, const std::vector<io::StampedPose>& est_raw,
                     const AteOptions& options) {
  const std::vector<io::StampedPose> gt = sortedUniqueByTimestamp(gt_raw);
  const std::vector<io::StampedPose> est = sortedUniqueByTimestamp(est_raw);
  const auto matches = associate(timestampsOf(gt), timestampsOf(est), options.association);
  core::require(matches.size() >= 2,
                fmt::format("ATE: only {} of {} estimated poses have a ground-truth pose within {} s; wrong sequence "
                            "or time offset?",
                            matches.size(), est.size(), options.association.max_difference_s));

  AteResult result;
  std::vector<Eigen::Vector3d> est_positions;
  for (const auto& [g, e] : matches) {
    result.gt_stamps.push_back(gt[g].timestamp);
    result.est_stamps.push_back(est[e].timestamp);
    result.gt_positions.push_back(gt[g].T_wc.translation());
    est_positions.push_back(est[e].T_wc.translation());
  }
  result.alignment = alignPoints(est_positions, result.gt_positions, options.with_scale);
  for (std::size_t i = 0; i < est_positions.size(); ++i) {
    result.est_positions_aligned.push_back(result.alignment.apply(est_positions[i]));
    result.errors_m.push_back((result.est_positions_aligned.back() - result.gt_positions[i]).norm());
  }
  result.error_m = computeErrorStats(result.errors_m);
  return result;
}

}  // namespace amos::eval
