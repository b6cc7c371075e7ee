#include "amos/eval/jitter.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "amos/core/error.h"
#include "amos/core/pose.h"

namespace amos::eval {

void JitterOptions::check() const {
  core::require(association.max_difference_s > 0 && std::isfinite(association.max_difference_s),
                "eval.max_time_difference must be a positive number of seconds");
  core::require(std::isfinite(association.offset_s), "eval.time_offset must be finite");
  core::require(scale > 0 && std::isfinite(scale), "jitter scale must be positive");
}

JitterResult computeJitter(const std::vector<io::StampedPose>& gt_raw, const std::vector<io::StampedPose>& est_raw,
                           const JitterOptions& options) {
  options.check();
  const std::vector<io::StampedPose> gt = sortedUniqueByTimestamp(gt_raw);
  const std::vector<io::StampedPose> est = sortedUniqueByTimestamp(est_raw);
  std::vector<std::pair<std::size_t, std::size_t>> matches =  // (gt, est)
      associate(timestampsOf(gt), timestampsOf(est), options.association);
  std::sort(matches.begin(), matches.end(), [](const auto& a, const auto& b) { return a.second < b.second; });

  JitterResult r;
  std::vector<double> intervals;
  for (std::size_t k = 1; k < matches.size(); ++k)
    intervals.push_back(est[matches[k].second].timestamp - est[matches[k - 1].second].timestamp);
  const double max_interval = intervals.empty() ? 0 : 1.5 * computeErrorStats(intervals).median;

  std::vector<double> trans, rot_deg, est_steps, gt_steps;
  for (std::size_t k = 1; k < matches.size(); ++k) {
    const auto& [g0, e0] = matches[k - 1];
    const auto& [g1, e1] = matches[k];
    if (intervals[k - 1] > max_interval) {
      ++r.gaps;
      continue;
    }
    core::SE3 est_motion = est[e0].T_wc.inverse() * est[e1].T_wc;
    est_motion.translation() *= options.scale;
    const core::SE3 gt_motion = gt[g0].T_wc.inverse() * gt[g1].T_wc;
    const core::SE3 error = est_motion.inverse() * gt_motion;
    JitterStep s;
    s.est_stamp_0 = est[e0].timestamp;
    s.est_stamp_1 = est[e1].timestamp;
    s.est_step_m = est_motion.translation().norm();
    s.gt_step_m = gt_motion.translation().norm();
    s.trans_error_m = error.translation().norm();
    s.rot_error_rad = core::rotationAngle(error);
    trans.push_back(s.trans_error_m);
    rot_deg.push_back(s.rot_error_rad * 180.0 / M_PI);
    est_steps.push_back(s.est_step_m);
    gt_steps.push_back(s.gt_step_m);
    r.est_path_m += s.est_step_m;
    r.gt_path_m += s.gt_step_m;
    r.steps.push_back(s);
  }
  r.trans_m = computeErrorStats(trans);
  r.rot_deg = computeErrorStats(rot_deg);
  r.est_step_median_m = computeErrorStats(est_steps).median;
  r.gt_step_median_m = computeErrorStats(gt_steps).median;
  return r;
}

std::string jitterLine(const JitterResult& j) {
  if (j.steps.empty()) return "jitter (1 frame): n/a (no consecutive associated poses)\n";
  return fmt::format(
      "jitter (1 frame): RPE trans rmse {:.2f} mm, median {:.2f} mm; rot median {:.3f} deg; step median "
      "estimate {:.2f} mm / ground truth {:.2f} mm; path estimate {:.3f} m / ground truth {:.3f} m ({} pairs{})\n",
      1000 * j.trans_m.rmse, 1000 * j.trans_m.median, j.rot_deg.median, 1000 * j.est_step_median_m,
      1000 * j.gt_step_median_m, j.est_path_m, j.gt_path_m, j.steps.size(),
      j.gaps ? fmt::format(", {} gaps left out", j.gaps) : "");
}

}  // namespace amos::eval
