#include "amos/eval/alignment.h"

#include <Eigen/SVD>

#include "amos/core/error.h"

namespace amos::eval {

core::SE3 Alignment::apply(const core::SE3& T_wc) const {
  core::SE3 out = core::SE3::Identity();
  out.linear() = transform.linear() * T_wc.linear();
  out.translation() = apply(Eigen::Vector3d(T_wc.translation()));
  return out;
}

Alignment alignPoints(const std::vector<Eigen::Vector3d>& model, const std::vector<Eigen::Vector3d>& data,
                      bool with_scale) {
  core::require(model.size() == data.size(), "alignment: point lists differ in length");
  core::require(model.size() >= 2, "alignment: need at least two corresponding points");
  const double n = static_cast<double>(model.size());
  Eigen::Vector3d mean_model = Eigen::Vector3d::Zero(), mean_data = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < model.size(); ++i) {
    mean_model += model[i];
    mean_data += data[i];
  }
  mean_model /= n;
  mean_data /= n;

  // Cross-covariance of the centred point sets and the model's spread (for the scale).
  Eigen::Matrix3d W = Eigen::Matrix3d::Zero();
  double model_spread = 0;
  for (std::size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3d m = model[i] - mean_model;
    W += (data[i] - mean_data) * m.transpose();
    model_spread += m.squaredNorm();
  }
  // W = U D V^T; R = U S V^T with S fixing a reflection to a proper rotation (Umeyama's S).
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(W, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d& U = svd.matrixU();
  const Eigen::Matrix3d& V = svd.matrixV();
  Eigen::Vector3d S(1, 1, 1);
  if (U.determinant() * V.determinant() < 0) S.z() = -1;
  const Eigen::Matrix3d R = U * S.asDiagonal() * V.transpose();

  Alignment alignment;
  if (with_scale) {
    core::require(model_spread > 0, "alignment: the estimated points all coincide, scale is undefined");
    alignment.scale = svd.singularValues().dot(S) / model_spread;
  }
  alignment.transform.linear() = R;
  alignment.transform.translation() = mean_data - alignment.scale * R * mean_model;
  return alignment;
}

}  // namespace amos::eval
