#include "amos/loop/pose_graph.h"

#include <fmt/format.h>
#include <ceres/ceres.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::loop {

void PoseGraphOptions::check() const {
  core::requireOption(max_iterations >= 1, core::option(max_iterations, "max_iterations"),
                      fmt::format("must be >= 1, got {}", max_iterations));
}

namespace {

// Residual of one relative-pose edge; parameters: q_i (x y z w), t_i, q_j, t_j of the world-to-camera poses.
struct RelativePoseError {
  RelativePoseError(const core::SE3& T_ij, double weight, double rotation_scale)
      : q_ij(Eigen::Quaterniond(T_ij.linear()).normalized()),
        t_ij(T_ij.translation()),
        w(weight),
        rotation_scale(rotation_scale) {}

  template <typename T>
  bool operator()(const T* q_i_ptr, const T* t_i_ptr, const T* q_j_ptr, const T* t_j_ptr, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q_i(q_i_ptr), q_j(q_j_ptr);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t_i(t_i_ptr), t_j(t_j_ptr);
    // T_i * T_j^-1 = (q_i q_j^-1, t_i - q_i q_j^-1 t_j)
    const Eigen::Quaternion<T> q_j_inv = q_j.conjugate();
    const Eigen::Quaternion<T> q_est = q_i * q_j_inv;
    const Eigen::Matrix<T, 3, 1> t_est = t_i - q_est * t_j;
    // Error T_meas^-1 * T_est.
    const Eigen::Quaternion<T> q_meas_inv = q_ij.conjugate().template cast<T>();
    const Eigen::Quaternion<T> q_err = q_meas_inv * q_est;
    const Eigen::Matrix<T, 3, 1> t_err = q_meas_inv * (t_est - t_ij.template cast<T>());
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
    r.template head<3>() = T(2.0 * rotation_scale) * q_err.vec();
    r.template tail<3>() = t_err;
    r *= T(w);
    return true;
  }

  Eigen::Quaterniond q_ij;
  Eigen::Vector3d t_ij;
  double w;
  double rotation_scale;
};

}  // namespace

PoseGraphResult optimizePoseGraph(const std::vector<core::SE3>& T_iw, const std::vector<bool>& fixed,
                                  const std::vector<PoseGraphEdge>& edges, const PoseGraphOptions& options) {
  options.check();
  core::require(fixed.size() == T_iw.size(), "optimizePoseGraph: one fixed flag per vertex expected");
  core::require(std::any_of(fixed.begin(), fixed.end(), [](bool f) { return f; }),
                "optimizePoseGraph: at least one vertex must be fixed");
  const std::size_t n = T_iw.size();
  std::vector<std::array<double, 4>> q(n);
  std::vector<std::array<double, 3>> t(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Quaterniond qk(T_iw[k].linear());
    q[k] = {qk.x(), qk.y(), qk.z(), qk.w()};
    const Eigen::Vector3d tk = T_iw[k].translation();
    t[k] = {tk.x(), tk.y(), tk.z()};
  }
  ceres::Problem problem;
  std::vector<bool> added(n, false);
  for (const PoseGraphEdge& e : edges) {
    core::require(e.i >= 0 && e.j >= 0 && static_cast<std::size_t>(e.i) < n && static_cast<std::size_t>(e.j) < n &&
                      e.i != e.j,
                  "optimizePoseGraph: edge with an invalid vertex");
    core::require(e.weight > 0 && e.rotation_scale > 0, "optimizePoseGraph: edge weights must be positive");
    auto* cost = new ceres::AutoDiffCostFunction<RelativePoseError, 6, 4, 3, 4, 3>(
        new RelativePoseError(e.T_ij, e.weight, e.rotation_scale));
    problem.AddResidualBlock(cost, nullptr, q[e.i].data(), t[e.i].data(), q[e.j].data(), t[e.j].data());
    for (const int v : {e.i, e.j}) {
      if (added[v]) continue;
      added[v] = true;
      problem.SetManifold(q[v].data(), new ceres::EigenQuaternionManifold);
      if (fixed[v]) {
        problem.SetParameterBlockConstant(q[v].data());
        problem.SetParameterBlockConstant(t[v].data());
      }
    }
  }
  PoseGraphResult result;
  if (problem.NumResidualBlocks() > 0) {
    ceres::Solver::Options solver_options;
    solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    solver_options.max_num_iterations = options.max_iterations;
    solver_options.num_threads = 1;
    solver_options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    result.initial_cost = summary.initial_cost;
    result.final_cost = summary.final_cost;
    result.iterations = static_cast<int>(summary.iterations.size());
  }
  result.T_iw.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    result.T_iw[k] = core::makeSE3(Eigen::Quaterniond(q[k][3], q[k][0], q[k][1], q[k][2]),
                                   Eigen::Vector3d(t[k][0], t[k][1], t[k][2]));
  }
  return result;
}

}  // namespace amos::loop
