#pragma once
// Frame-to-frame jitter: the relative pose error over one frame. The estimated poses are associated with the
// ground truth as for ATE (associate.py's rule, eval.max_time_difference); for each two consecutive associated
// estimated poses (E_k, E_k+1) and the ground-truth poses associated with them (G_k, G_k+1), the error is
// inv(inv(E_k) E_k+1) * inv(G_k) G_k+1 (as RPE, rpe.h), its translation and rotation angle. Beside it, each step's
// length in the estimate and in the ground truth, and the path lengths (sums of the steps) over the same pairs: an
// estimate that scatters by more than the camera moves per frame has an RPE over one frame near its own step and
// a path longer than the ground truth's.
// A pair of consecutive estimated poses further apart than 1.5 x the median estimated interval (a stretch where
// tracking was lost and no pose was written) is not a one-frame step and is left out (`gaps`).
// No alignment: RPE is invariant to a rigid change of the world frame; with Sim(3) the estimate's steps are
// multiplied by the alignment's scale.
#include <cstddef>
#include <string>
#include <vector>

#include "amos/eval/associate.h"
#include "amos/eval/stats.h"
#include "amos/io/trajectory.h"

namespace amos::eval {

struct JitterOptions {
  AssociationOptions association;  // as ATE's
  double scale = 1.0;              // multiplies the estimate's steps (the Sim(3) alignment's scale)
  void check() const;
};

struct JitterStep {
  double est_stamp_0 = 0, est_stamp_1 = 0;  // the two estimated poses
  double est_step_m = 0, gt_step_m = 0;     // step lengths
  double trans_error_m = 0, rot_error_rad = 0;
};

struct JitterResult {
  ErrorStats trans_m;  // RPE over one frame, translation, metres
  ErrorStats rot_deg;  // and rotation, degrees
  double gt_step_median_m = ErrorStats::kNaN, est_step_median_m = ErrorStats::kNaN;
  double gt_path_m = 0, est_path_m = 0;  // sums of the steps compared
  std::size_t gaps = 0;                  // consecutive pairs left out as spanning more than one frame
  std::vector<JitterStep> steps;         // in time order
};

// Inputs in any order; duplicate stamps keep the last pose. Fewer than two associated poses give no step (NaN
// statistics), not an error.
JitterResult computeJitter(const std::vector<io::StampedPose>& gt, const std::vector<io::StampedPose>& est,
                           const JitterOptions& options = {});

// The figures in one line (millimetres and degrees), ending in a newline: `amos-slam eval` and `run` print it.
std::string jitterLine(const JitterResult& j);

}  // namespace amos::eval
