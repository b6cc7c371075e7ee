#include "amos/geometry/pose_optimizer.h"

#include <fmt/format.h>
#include <Eigen/Cholesky>
#include <cmath>
#include <string>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::geometry {

void PoseOptimizerOptions::check() const {
  core::requirePositive(chi2_mono, "chi2_mono");
  core::requirePositive(chi2_stereo, "chi2_stereo");
  core::requireAtLeast(rounds, "rounds", 1);
  core::requireAtLeast(iterations_per_round, "iterations_per_round", 1);
  core::requireAtLeast(robust_rounds, "robust_rounds", 0);
}

bool poseObservationResidual(const PoseObservation& obs, const core::SE3& T_cw, const StereoProjection& proj,
                             Eigen::Vector3d& residual, Eigen::Vector3d& point_c) {
  point_c = T_cw * obs.point_w;
  if (point_c.z() <= 1e-6) return false;
  const double inv_z = 1.0 / point_c.z();
  const double u = proj.fx * point_c.x() * inv_z + proj.cx;
  const double v = proj.fy * point_c.y() * inv_z + proj.cy;
  residual.x() = obs.pixel.x() - u;
  residual.y() = obs.pixel.y() - v;
  residual.z() = obs.u_right >= 0 ? obs.u_right - (u - proj.bf * inv_z) : 0.0;
  return true;
}

bool poseObservationJacobian(const PoseObservation& obs, const core::SE3& T_cw, const StereoProjection& proj,
                             Eigen::Vector3d& residual, Eigen::Matrix<double, 3, 6>& J) {
  Eigen::Vector3d pc;
  if (!poseObservationResidual(obs, T_cw, proj, residual, pc)) return false;
  const double inv_z = 1.0 / pc.z();
  const double inv_z2 = inv_z * inv_z;
  // d(projection)/d(point_c)
  Eigen::Matrix<double, 3, 3> Jp;
  Jp << proj.fx * inv_z, 0, -proj.fx * pc.x() * inv_z2,  //
      0, proj.fy * inv_z, -proj.fy * pc.y() * inv_z2,     //
      proj.fx * inv_z, 0, -proj.fx * pc.x() * inv_z2 + proj.bf * inv_z2;
  // d(point_c)/d(delta) for T <- exp(delta) T: [I, -[p_c]x]
  Eigen::Matrix<double, 3, 6> Jd;
  Jd.leftCols<3>().setIdentity();
  Jd.rightCols<3>() = -core::skew(pc);
  // residual = observed - predicted, so J_r = -Jp * Jd
  J = -(Jp * Jd);
  return true;
}

namespace {

// Weighted chi2 of one observation (residual^T * inv_sigma2 * residual).
double chi2Of(const PoseObservation& obs, const Eigen::Vector3d& r) {
  const double sq = obs.u_right >= 0 ? r.squaredNorm() : r.head<2>().squaredNorm();
  return sq * obs.inv_sigma2;
}

// Huber IRLS weight for a whitened squared error e2 with threshold delta^2 = chi2 threshold.
double poseHuberWeight(double e2, double delta2) {
  if (e2 <= delta2) return 1.0;
  return std::sqrt(delta2 / e2);
}

// Sum of (robustified) costs over the active observations, for the LM acceptance test.
double totalCost(const std::vector<PoseObservation>& obs, const std::vector<bool>& active, const core::SE3& T,
                 const StereoProjection& proj, const PoseOptimizerOptions& o, bool robust) {
  double cost = 0;
  Eigen::Vector3d r, pc;
  for (std::size_t i = 0; i < obs.size(); ++i) {
    if (!active[i]) continue;
    const double delta2 = obs[i].u_right >= 0 ? o.chi2_stereo : o.chi2_mono;
    if (!poseObservationResidual(obs[i], T, proj, r, pc)) {
      cost += 2 * delta2;  // behind the camera: a large, bounded penalty
      continue;
    }
    const double e2 = chi2Of(obs[i], r);
    if (robust && e2 > delta2) {
      cost += 2 * std::sqrt(delta2 * e2) - delta2;
    } else {
      cost += e2;
    }
  }
  return cost;
}

}  // namespace

PoseOptimizerResult optimizePose(const std::vector<PoseObservation>& obs, const core::SE3& initial_T_cw,
                                 const StereoProjection& proj, const PoseOptimizerOptions& o) {
  PoseOptimizerResult result;
  result.T_cw = initial_T_cw;
  result.outlier.resize(obs.size());
  for (std::size_t i = 0; i < obs.size(); ++i) result.outlier[i] = obs[i].outlier;
  if (obs.empty()) return result;

  std::vector<bool> active(obs.size());
  Eigen::Vector3d r, pc;
  Eigen::Matrix<double, 3, 6> J;
  for (int round = 0; round < o.rounds; ++round) {
    const bool robust = round < o.robust_rounds;
    for (std::size_t i = 0; i < obs.size(); ++i) active[i] = !result.outlier[i];
    double lambda = 1e-4;
    double cost = totalCost(obs, active, result.T_cw, proj, o, robust);
    for (int it = 0; it < o.iterations_per_round; ++it) {
      Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
      core::Vector6d g = core::Vector6d::Zero();
      int used = 0;
      for (std::size_t i = 0; i < obs.size(); ++i) {
        if (!active[i]) continue;
        if (!poseObservationJacobian(obs[i], result.T_cw, proj, r, J)) continue;
        const bool stereo = obs[i].u_right >= 0;
        const double delta2 = stereo ? o.chi2_stereo : o.chi2_mono;
        const double w = obs[i].inv_sigma2 * (robust ? poseHuberWeight(chi2Of(obs[i], r), delta2) : 1.0);
        const int rows = stereo ? 3 : 2;
        H.noalias() += w * J.topRows(rows).transpose() * J.topRows(rows);
        g.noalias() += w * J.topRows(rows).transpose() * r.head(rows);
        ++used;
      }
      if (used < 3) break;
      // Levenberg-Marquardt: try steps with growing damping until the cost goes down.
      bool improved = false;
      for (int attempt = 0; attempt < 10; ++attempt) {
        Eigen::Matrix<double, 6, 6> Hd = H;
        Hd.diagonal() += lambda * (H.diagonal().array() + 1e-9).matrix();
        const core::Vector6d delta = Hd.ldlt().solve(-g);
        if (!delta.allFinite()) {
          lambda *= 10;
          continue;
        }
        const core::SE3 candidate = core::expSE3(delta) * result.T_cw;
        const double new_cost = totalCost(obs, active, candidate, proj, o, robust);
        if (new_cost <= cost) {
          result.T_cw = candidate;
          const double decrease = cost - new_cost;
          cost = new_cost;
          lambda = std::max(lambda / 10, 1e-9);
          improved = true;
          if (delta.squaredNorm() < 1e-14 || decrease < 1e-10 * (cost + 1e-12)) it = o.iterations_per_round;
          break;
        }
        lambda *= 10;
      }
      if (!improved) break;
    }
    // Classify every observation (including earlier outliers) against the refined pose.
    result.num_inliers = 0;
    result.final_chi2 = 0;
    for (std::size_t i = 0; i < obs.size(); ++i) {
      const double delta2 = obs[i].u_right >= 0 ? o.chi2_stereo : o.chi2_mono;
      if (!poseObservationResidual(obs[i], result.T_cw, proj, r, pc)) {
        result.outlier[i] = true;
        continue;
      }
      const double e2 = chi2Of(obs[i], r);
      result.outlier[i] = e2 > delta2;
      if (!result.outlier[i]) {
        ++result.num_inliers;
        result.final_chi2 += e2;
      }
    }
    if (result.num_inliers < 10 && round + 1 >= 2) break;  // too few left to refine further
  }
  return result;
}

}  // namespace amos::geometry
