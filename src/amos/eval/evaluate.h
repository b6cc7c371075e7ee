#pragma once
// The one call a SLAM run (and `amos-slam eval`) makes: ATE and RPE of an estimated trajectory against ground
// truth, with the TUM benchmark's conventions (evaluate_ate.py; evaluate_rpe.py --fixed_delta --delta 1
// --delta_unit s), and the result as JSON.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "amos/eval/ate.h"
#include "amos/eval/jitter.h"
#include "amos/eval/rpe.h"
#include "amos/io/trajectory.h"

namespace amos::eval {

struct EvaluationOptions {
  double max_time_difference_s = 0.02;  // eval.max_time_difference: ATE association radius, seconds
  double time_offset_s = 0.0;           // eval.time_offset: added to the estimate's stamps
  bool sim3 = false;                    // eval.sim3: similarity instead of rigid alignment for ATE (and the
                                        //   ATE scale then multiplies the estimate's relative motions for RPE)
  double rpe_delta_s = 1.0;             // eval.rpe_delta: RPE pose-pair spacing, seconds
  std::size_t rpe_max_pairs = 10000;    // eval.rpe_max_pairs: RPE subsampling threshold, 0 = never
  std::uint32_t rpe_seed = 0;           // eval.rpe_seed: seed of that subsampling
  // Throws core::Error naming the eval.* key whose value is invalid.
  void check() const;
};

struct EvaluationResult {
  // Headline figures (NaN when there is nothing to compare, e.g. RPE of an estimate shorter than delta).
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double ate_rmse_m = kNaN, ate_mean_m = kNaN, ate_median_m = kNaN, ate_std_m = kNaN, ate_min_m = kNaN,
         ate_max_m = kNaN;
  std::size_t ate_pairs = 0;
  double rpe_trans_rmse_m = kNaN, rpe_rot_rmse_deg = kNaN;
  std::size_t rpe_pairs = 0;
  double rpe_delta_s = 1.0;
  std::size_t gt_poses = 0, est_poses = 0;  // after removing duplicate stamps
  Alignment alignment;  // estimate -> ground-truth frame (scale 1 unless sim3)
  bool sim3 = false;
  // Details: per-pair ATE errors and positions, RPE pairs and full statistics.
  AteResult ate;
  RpeResult rpe;
  JitterResult jitter;  // RPE over one frame, step lengths and path lengths (jitter.h)
};

// Throws core::Error when either trajectory is empty, or fewer than two estimated poses associate with ground truth.
EvaluationResult evaluate(const std::vector<io::StampedPose>& gt, const std::vector<io::StampedPose>& est,
                          const EvaluationOptions& options = {});

// Keys: ate_rmse_m ate_mean_m ate_median_m ate_std_m ate_min_m ate_max_m ate_pairs rpe_trans_rmse_m
// rpe_trans_mean_m rpe_trans_median_m rpe_trans_max_m rpe_rot_rmse_deg rpe_rot_mean_deg rpe_rot_median_deg
// rpe_rot_max_deg rpe_pairs rpe_delta_s gt_poses est_poses alignment{type, scale, rotation (row-major 3x3),
// translation} jitter{rpe1_trans_rmse_m, rpe1_trans_median_m, rpe1_rot_rmse_deg, rpe1_rot_median_deg,
// gt_step_median_m, est_step_median_m, est_path_m, gt_path_m, pairs, gaps}. NaN values become null.
nlohmann::json toJson(const EvaluationResult& result);

}  // namespace amos::eval
