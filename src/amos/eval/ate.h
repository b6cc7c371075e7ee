#pragma once
// Absolute trajectory error as the TUM benchmark's evaluate_ate.py computes it: associate ground-truth and
// estimated stamps (associate.py), align the estimated positions onto the ground-truth positions (Horn, rigid by
// default), then the per-pair position error |gt_i - align(est_i)|.
#include <vector>

#include "amos/eval/alignment.h"
#include "amos/eval/associate.h"
#include "amos/eval/stats.h"
#include "amos/io/trajectory.h"

namespace amos::eval {

struct AteOptions {
  AssociationOptions association;
  bool with_scale = false;  // eval.sim3: similarity alignment (monocular estimates)
};

struct AteResult {
  ErrorStats error_m;   // over the associated pairs, metres
  Alignment alignment;  // maps the estimate into the ground-truth frame
  // Per associated pair, sorted by ground-truth stamp:
  std::vector<double> gt_stamps, est_stamps, errors_m;
  std::vector<Eigen::Vector3d> gt_positions, est_positions_aligned;
};

// Inputs in any order; duplicate stamps keep the last pose (see sortedUniqueByTimestamp). Throws core::Error
// when fewer than two pairs associate (evaluate_ate.py exits in that case).
AteResult computeAte(const std::vector<io::StampedPose>& gt, const std::vector<io::StampedPose>& est,
                     const AteOptions& options = {});

}  // namespace amos::eval
