#include "amos/mapping/bundle_adjustment.h"

#include <fmt/format.h>
#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <memory>
#include <string>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::mapping {

void BundleAdjustmentOptions::check() const {
  core::requireAtLeast(iterations_robust, "iterations_robust", 1);
  core::requireAtLeast(iterations_refine, "iterations_refine", 0);
  core::requirePositive(chi2_mono, "chi2_mono");
  core::requirePositive(chi2_stereo, "chi2_stereo");
  core::requireAtLeast(num_threads, "num_threads", 1);
  core::requireAtLeast(max_keyframes, "max_keyframes", 0);
}

namespace {

constexpr double kChi2SixDof95 = 12.592;

// Pose parameter block: [tx ty tz qx qy qz qw] of T_cw.
using PoseBlock = std::array<double, 7>;

PoseBlock toBlock(const core::SE3& T) {
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d t = T.translation();
  return {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
}

core::SE3 fromBlock(const double* b) {
  return core::makeSE3(Eigen::Quaterniond(b[6], b[3], b[4], b[5]), Eigen::Vector3d(b[0], b[1], b[2]));
}

// SE(3) with left perturbation T <- exp(delta) T (core/pose.h convention). The cost functions return their
// Jacobians directly in the 6-d tangent (padded with a zero column), so PlusJacobian is [I6; 0].
class Se3LeftManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 7; }
  int TangentSize() const override { return 6; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    const core::SE3 T = core::expSE3(Eigen::Map<const core::Vector6d>(delta)) * fromBlock(x);
    const PoseBlock b = toBlock(T);
    std::copy(b.begin(), b.end(), x_plus_delta);
    return true;
  }
  bool PlusJacobian(const double*, double* jacobian) const override {
    Eigen::Map<Eigen::Matrix<double, 7, 6, Eigen::RowMajor>> J(jacobian);
    J.setZero();
    J.topRows<6>().setIdentity();
    return true;
  }
  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    Eigen::Map<core::Vector6d> out(y_minus_x);
    out = core::logSE3(fromBlock(y) * fromBlock(x).inverse());
    return true;
  }
  bool MinusJacobian(const double*, double* jacobian) const override {
    Eigen::Map<Eigen::Matrix<double, 6, 7, Eigen::RowMajor>> J(jacobian);
    J.setZero();
    J.leftCols<6>().setIdentity();
    return true;
  }
};

// Whitened reprojection residual sqrt(inv_sigma2) * (predicted - observed) of one observation.
class ReprojectionCost final : public ceres::CostFunction {
 public:
  ReprojectionCost(const BaObservation& obs, const geometry::StereoProjection& proj)
      : obs_(obs), proj_(proj), stereo_(obs.u_right >= 0), sqrt_info_(std::sqrt(obs.inv_sigma2)) {
    set_num_residuals(stereo_ ? 3 : 2);
    *mutable_parameter_block_sizes() = {7, 3};
  }

  bool Evaluate(double const* const* params, double* residuals, double** jacobians) const override {
    const core::SE3 T = fromBlock(params[0]);
    const Eigen::Map<const Eigen::Vector3d> pw(params[1]);
    const Eigen::Vector3d pc = T * pw;
    // A point that drifts behind the camera keeps a finite residual; it is classified as an outlier later.
    const double z = std::max(pc.z(), 1e-3);
    const double inv_z = 1.0 / z;
    const double u = proj_.fx * pc.x() * inv_z + proj_.cx;
    const double v = proj_.fy * pc.y() * inv_z + proj_.cy;
    residuals[0] = sqrt_info_ * (u - obs_.pixel.x());
    residuals[1] = sqrt_info_ * (v - obs_.pixel.y());
    if (stereo_) residuals[2] = sqrt_info_ * (u - proj_.bf * inv_z - obs_.u_right);
    if (!jacobians) return true;
    Eigen::Matrix3d Jp;
    const double inv_z2 = inv_z * inv_z;
    Jp << proj_.fx * inv_z, 0, -proj_.fx * pc.x() * inv_z2,  //
        0, proj_.fy * inv_z, -proj_.fy * pc.y() * inv_z2,     //
        proj_.fx * inv_z, 0, -proj_.fx * pc.x() * inv_z2 + proj_.bf * inv_z2;
    Jp *= sqrt_info_;
    const int rows = stereo_ ? 3 : 2;
    if (jacobians[0]) {
      Eigen::Matrix<double, 3, 6> Jd;
      Jd.leftCols<3>().setIdentity();
      Jd.rightCols<3>() = -core::skew(pc);
      const Eigen::Matrix<double, 3, 6> J = Jp * Jd;
      for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < 6; ++c) jacobians[0][r * 7 + c] = J(r, c);
        jacobians[0][r * 7 + 6] = 0;
      }
    }
    if (jacobians[1]) {
      const Eigen::Matrix3d J = Jp * T.linear();
      for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < 3; ++c) jacobians[1][r * 3 + c] = J(r, c);
      }
    }
    return true;
  }

 private:
  BaObservation obs_;
  geometry::StereoProjection proj_;
  bool stereo_;
  double sqrt_info_;
};

// Whitened relative-pose residual L^T log(E), E = T_a T_b^-1 T_ab^-1, information = L L^T. In the left tangent of
// each pose: exp(d) T_a turns E into exp(d) E, and exp(d) T_b turns it into exp(-Ad(T_a T_b^-1) d) E, so with J the
// inverse left Jacobian of SE(3) at log(E) the derivatives are L^T J and -L^T J Ad(T_a T_b^-1).
class RelativePoseCost final : public ceres::CostFunction {
 public:
  explicit RelativePoseCost(const BaRelativePose& rel) : T_ba_meas_(rel.T_ab.inverse()) {
    const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(rel.information);
    sqrt_info_ = llt.info() == Eigen::Success ? Eigen::Matrix<double, 6, 6>(llt.matrixU())
                                              : Eigen::Matrix<double, 6, 6>::Zero();
    set_num_residuals(6);
    mutable_parameter_block_sizes()->push_back(7);
    mutable_parameter_block_sizes()->push_back(7);
  }

  bool Evaluate(double const* const* params, double* residuals, double** jacobians) const override {
    const core::SE3 T_ab_est = fromBlock(params[0]) * fromBlock(params[1]).inverse();
    const core::Vector6d error = core::logSE3(T_ab_est * T_ba_meas_);
    Eigen::Map<core::Vector6d> out(residuals);
    out = sqrt_info_ * error;
    if (!jacobians) return true;
    const core::Matrix6d d_error = sqrt_info_ * core::leftJacobianInverseSE3(error);
    for (int block = 0; block < 2; ++block) {
      if (!jacobians[block]) continue;
      Eigen::Map<Eigen::Matrix<double, 6, 7, Eigen::RowMajor>> J(jacobians[block]);
      J.setZero();
      J.leftCols<6>() = block == 0 ? d_error : core::Matrix6d(-d_error * core::adjointSE3(T_ab_est));
    }
    return true;
  }

 private:
  core::SE3 T_ba_meas_;
  Eigen::Matrix<double, 6, 6> sqrt_info_;
};

class AbortCallback final : public ceres::IterationCallback {
 public:
  explicit AbortCallback(const std::atomic<bool>* abort) : abort_(abort) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    if (abort_ && abort_->load(std::memory_order_relaxed)) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const std::atomic<bool>* abort_;
};

// chi2 of one observation at the current estimate; false when the point is behind the camera.
bool observationChi2(const BaObservation& o, const core::SE3& T, const Eigen::Vector3d& p,
                     const geometry::StereoProjection& proj, double& chi2) {
  geometry::PoseObservation po;
  po.point_w = p;
  po.pixel = o.pixel;
  po.u_right = o.u_right;
  Eigen::Vector3d r, pc;
  if (!geometry::poseObservationResidual(po, T, proj, r, pc)) return false;
  chi2 = (o.u_right >= 0 ? r.squaredNorm() : r.head<2>().squaredNorm()) * o.inv_sigma2;
  return true;
}

}  // namespace

BaResult solveBundleAdjustment(const BaProblem& problem, const BundleAdjustmentOptions& options,
                               const std::atomic<bool>* abort) {
  options.check();
  BaResult result;
  std::vector<PoseBlock> poses(problem.keyframes.size());
  for (std::size_t k = 0; k < poses.size(); ++k) poses[k] = toBlock(problem.keyframes[k].T_cw);
  std::vector<Eigen::Vector3d> points(problem.points.size());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = problem.points[i].position;
  std::vector<bool> active(problem.observations.size(), true);

  auto isOutlier = [&](std::size_t j) {
    const BaObservation& o = problem.observations[j];
    double chi2 = 0;
    if (!observationChi2(o, fromBlock(poses[o.keyframe].data()), points[o.point], problem.projection, chi2)) return true;
    return chi2 > (o.u_right >= 0 ? options.chi2_stereo : options.chi2_mono);
  };

  // The cost functions and the two losses are made once and shared by both stages' problems (which do not own
  // them): per-residual heap objects, built twice, were a fifth of the solve's CPU in small windows.
  // (ceres::CostFunction cannot be moved: a deque keeps them in place.)
  std::deque<ReprojectionCost> costs;
  for (const BaObservation& o : problem.observations) costs.emplace_back(o, problem.projection);
  std::deque<RelativePoseCost> relative_costs;
  for (const BaRelativePose& rel : problem.relative_poses) relative_costs.emplace_back(rel);
  ceres::HuberLoss huber_mono(std::sqrt(options.chi2_mono)), huber_stereo(std::sqrt(options.chi2_stereo)),
      huber_relative(std::sqrt(kChi2SixDof95));

  auto solve = [&](int iterations, bool robust) {
    ceres::Problem::Options problem_options;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    Se3LeftManifold manifold;
    ceres::Problem ceres_problem(problem_options);
    std::vector<bool> pose_added(poses.size(), false);
    for (std::size_t j = 0; j < problem.observations.size(); ++j) {
      if (!active[j]) continue;
      const BaObservation& o = problem.observations[j];
      ceres::LossFunction* loss = robust ? (o.u_right >= 0 ? &huber_stereo : &huber_mono) : nullptr;
      ceres_problem.AddResidualBlock(&costs[j], loss, poses[o.keyframe].data(), points[o.point].data());
      if (!pose_added[o.keyframe]) {
        pose_added[o.keyframe] = true;
        ceres_problem.SetManifold(poses[o.keyframe].data(), &manifold);
        if (problem.keyframes[o.keyframe].fixed) ceres_problem.SetParameterBlockConstant(poses[o.keyframe].data());
      }
    }
    for (std::size_t r = 0; r < problem.relative_poses.size(); ++r) {
      const BaRelativePose& rel = problem.relative_poses[r];
      // Only between keyframes the observations put in the problem, and not between two fixed ones.
      if (!pose_added[rel.a] || !pose_added[rel.b]) continue;
      if (problem.keyframes[rel.a].fixed && problem.keyframes[rel.b].fixed) continue;
      ceres::LossFunction* loss = robust ? &huber_relative : nullptr;
      ceres_problem.AddResidualBlock(&relative_costs[r], loss, poses[rel.a].data(), poses[rel.b].data());
    }
    if (ceres_problem.NumResidualBlocks() == 0) return;
    ceres::Solver::Options solver_options;
    solver_options.linear_solver_type = ceres::DENSE_SCHUR;
    solver_options.max_num_iterations = iterations;
    solver_options.num_threads = options.num_threads;
    solver_options.logging_type = ceres::SILENT;
    solver_options.minimizer_progress_to_stdout = false;
    AbortCallback callback(abort);
    solver_options.callbacks.push_back(&callback);
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &ceres_problem, &summary);
    if (result.iterations == 0) result.initial_cost = summary.initial_cost;
    result.final_cost = summary.final_cost;
    result.iterations += static_cast<int>(summary.iterations.size());
  };

  solve(options.iterations_robust, true);
  result.aborted = abort && abort->load(std::memory_order_relaxed);
  if (!result.aborted && options.iterations_refine > 0) {
    for (std::size_t j = 0; j < active.size(); ++j) active[j] = !isOutlier(j);
    solve(options.iterations_refine, false);
    result.aborted = abort && abort->load(std::memory_order_relaxed);
  }
  result.T_cw.resize(poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) result.T_cw[k] = fromBlock(poses[k].data());
  result.positions = std::move(points);
  result.outlier.resize(problem.observations.size());
  for (std::size_t j = 0; j < problem.observations.size(); ++j) {
    const BaObservation& o = problem.observations[j];
    double chi2 = 0;
    const bool in_front =
        observationChi2(o, result.T_cw[o.keyframe], result.positions[o.point], problem.projection, chi2);
    result.outlier[j] = !in_front || chi2 > (o.u_right >= 0 ? options.chi2_stereo : options.chi2_mono);
  }
  return result;
}

}  // namespace amos::mapping
