#pragma once
// Closed-form alignment of corresponding 3D points (Horn 1987 / Umeyama 1991 via SVD), as the TUM benchmark's
// evaluate_ate.py does it: find R, t (and optionally s) minimising sum |data_i - (s R model_i + t)|^2.
// In the evaluator, model = estimated positions and data = ground-truth positions, so the estimate is moved
// onto the ground truth.
#include <vector>

#include "amos/core/pose.h"

namespace amos::eval {

// p_data = scale * R * p_model + t, with R, t in `transform`.
struct Alignment {
  core::SE3 transform = core::SE3::Identity();
  double scale = 1.0;  // 1 unless a similarity was requested

  Eigen::Vector3d apply(const Eigen::Vector3d& p) const {
    return transform.linear() * (scale * p) + transform.translation();
  }
  // A camera pose T_wc of the model trajectory expressed in the data frame: rotation R * R_wc, centre apply(t_wc).
  core::SE3 apply(const core::SE3& T_wc) const;
};

// Requires at least two pairs of equal count; throws core::Error otherwise. With fewer than three non-collinear
// points the rotation is not unique (the SVD picks one, like the script).
Alignment alignPoints(const std::vector<Eigen::Vector3d>& model, const std::vector<Eigen::Vector3d>& data,
                      bool with_scale);

}  // namespace amos::eval
