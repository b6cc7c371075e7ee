#include "amos/eval/evaluate.h"

#include <cmath>

#include "amos/core/error.h"
#include "amos/eval/associate.h"

namespace amos::eval {
namespace {

// nlohmann would write NaN as null anyway; being explicit keeps the intent visible.
nlohmann::json number(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

}  // namespace

void EvaluationOptions::check() const {
  core::require(max_time_difference_s > 0 && std::isfinite(max_time_difference_s),
                "eval.max_time_difference must be a positive number of seconds");
  core::require(std::isfinite(time_offset_s), "eval.time_offset must be finite");
  core::require(rpe_delta_s > 0 && std::isfinite(rpe_delta_s), "eval.rpe_delta must be a positive number of seconds");
}

EvaluationResult evaluate(const std::vector<io::StampedPose>& gt, const std::vector<io::StampedPose>& est,
                          const EvaluationOptions& options) {
  options.check();
  core::require(!gt.empty(), "the ground truth has no pose to compare with");
  core::require(!est.empty(), "the estimate has no pose to evaluate");
  EvaluationResult r;
  r.gt_poses = sortedUniqueByTimestamp(gt).size();
  r.est_poses = sortedUniqueByTimestamp(est).size();

  AteOptions ate_options;
  ate_options.association.max_difference_s = options.max_time_difference_s;
  ate_options.association.offset_s = options.time_offset_s;
  ate_options.with_scale = options.sim3;
  r.ate = computeAte(gt, est, ate_options);

  RpeOptions rpe_options;
  rpe_options.delta_s = options.rpe_delta_s;
  rpe_options.max_pairs = options.rpe_max_pairs;
  rpe_options.seed = options.rpe_seed;
  rpe_options.offset_s = options.time_offset_s;
  rpe_options.scale = r.ate.alignment.scale;  // 1 for rigid alignment: exactly the script's default
  r.rpe = computeRpe(gt, est, rpe_options);

  JitterOptions jitter_options;
  jitter_options.association = ate_options.association;
  jitter_options.scale = r.ate.alignment.scale;
  r.jitter = computeJitter(gt, est, jitter_options);

  const ErrorStats& a = r.ate.error_m;
  r.ate_rmse_m = a.rmse;
  r.ate_mean_m = a.mean;
  r.ate_median_m = a.median;
  r.ate_std_m = a.std_dev;
  r.ate_min_m = a.min;
  r.ate_max_m = a.max;
  r.ate_pairs = a.count;
  r.rpe_trans_rmse_m = r.rpe.trans_m.rmse;
  r.rpe_rot_rmse_deg = r.rpe.rot_deg.rmse;
  r.rpe_pairs = r.rpe.pairs.size();
  r.rpe_delta_s = options.rpe_delta_s;
  r.alignment = r.ate.alignment;
  r.sim3 = options.sim3;
  return r;
}

nlohmann::json toJson(const EvaluationResult& r) {
  nlohmann::json j;
  j["ate_rmse_m"] = number(r.ate_rmse_m);
  j["ate_mean_m"] = number(r.ate_mean_m);
  j["ate_median_m"] = number(r.ate_median_m);
  j["ate_std_m"] = number(r.ate_std_m);
  j["ate_min_m"] = number(r.ate_min_m);
  j["ate_max_m"] = number(r.ate_max_m);
  j["ate_pairs"] = r.ate_pairs;
  j["rpe_trans_rmse_m"] = number(r.rpe_trans_rmse_m);
  j["rpe_trans_mean_m"] = number(r.rpe.trans_m.mean);
  j["rpe_trans_median_m"] = number(r.rpe.trans_m.median);
  j["rpe_trans_max_m"] = number(r.rpe.trans_m.max);
  j["rpe_rot_rmse_deg"] = number(r.rpe_rot_rmse_deg);
  j["rpe_rot_mean_deg"] = number(r.rpe.rot_deg.mean);
  j["rpe_rot_median_deg"] = number(r.rpe.rot_deg.median);
  j["rpe_rot_max_deg"] = number(r.rpe.rot_deg.max);
  j["rpe_pairs"] = r.rpe_pairs;
  j["rpe_delta_s"] = r.rpe_delta_s;
  j["gt_poses"] = r.gt_poses;
  j["est_poses"] = r.est_poses;
  const Eigen::Matrix3d R = r.alignment.transform.linear();
  const Eigen::Vector3d t = r.alignment.transform.translation();
  j["alignment"] = {{"type", r.sim3 ? "sim3" : "se3"},
                    {"scale", r.alignment.scale},
                    {"rotation", {R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2)}},
                    {"translation", {t.x(), t.y(), t.z()}}};
  const JitterResult& jt = r.jitter;
  j["jitter"] = {{"rpe1_trans_rmse_m", number(jt.trans_m.rmse)},
                 {"rpe1_trans_median_m", number(jt.trans_m.median)},
                 {"rpe1_rot_rmse_deg", number(jt.rot_deg.rmse)},
                 {"rpe1_rot_median_deg", number(jt.rot_deg.median)},
                 {"gt_step_median_m", number(jt.gt_step_median_m)},
                 {"est_step_median_m", number(jt.est_step_median_m)},
                 {"est_path_m", number(jt.est_path_m)},
                 {"gt_path_m", number(jt.gt_path_m)},
                 {"pairs", jt.steps.size()},
                 {"gaps", jt.gaps}};
  return j;
}

}  // namespace amos::eval
