#include "amos/geometry/pnp_ransac.h"

#include <fmt/format.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/geometry/epnp.h"

namespace amos::geometry {

void PnpRansacOptions::check() const {
  core::requirePositive(reprojection_threshold_px, "reprojection_threshold_px");
  core::requireOption(confidence > 0 && confidence < 1, core::option(confidence, "confidence"),
                      fmt::format("must be in (0, 1), got {}", confidence));
  core::requirePositive(max_iterations, "max_iterations");
  core::requireAtLeast(min_inliers, "min_inliers", 4);
  core::requireAtLeast(coverage_cols, "coverage_cols", 0);
  core::requireAtLeast(coverage_rows, "coverage_rows", 0);
  core::requireOption(coverage_min_support >= 0 && coverage_min_support <= 1,
                      core::option(coverage_min_support, "coverage_min_support"),
                      fmt::format("must be in [0, 1], got {}", coverage_min_support));
}

namespace {

// EPnP is well conditioned from 5 points on (OpenCV's own RANSAC uses 5 for EPnP too); 4 would be the minimum.
constexpr int kEpnpSampleSize = 5;
constexpr int kP3pSampleSize = 3;
// Support a pose needs at the least, whichever solver drew it: more than the 5 points EPnP fits exactly (a 3-point
// AP3P sample is held to the same bar, so that both solvers accept the same poses).
constexpr int kMinSupport = kEpnpSampleSize + 1;
constexpr int kMaxSampleSize = kEpnpSampleSize;
// Gauss-Newton rounds of the final refinement and re-evaluations of the inlier set after it.
constexpr int kRefineIterations = 10;
constexpr int kLocalRefineIterations = 3;
constexpr int kInlierRounds = 10;

// Squared reprojection error of one correspondence, +inf when the point is not in front of the camera.
double squaredError(const core::SE3& T_cw, const Eigen::Vector3d& p_w, const Eigen::Vector2d& uv,
                    const core::PinholeCamera& camera) {
  const Eigen::Vector3d p_c = T_cw * p_w;
  if (p_c.z() <= 1e-9) return std::numeric_limits<double>::infinity();
  return (camera.project(p_c) - uv).squaredNorm();
}

// Inliers of a pose; returns their count and fills `inliers` (sorted indices).
int collectInliers(const core::SE3& T_cw, const std::vector<Eigen::Vector3d>& points_w,
                   const std::vector<Eigen::Vector2d>& pixels, const core::PinholeCamera& camera, double threshold2,
                   std::vector<int>& inliers) {
  inliers.clear();
  for (size_t i = 0; i < points_w.size(); ++i)
    if (squaredError(T_cw, points_w[i], pixels[i], camera) < threshold2) inliers.push_back(static_cast<int>(i));
  return static_cast<int>(inliers.size());
}

int countInliers(const core::SE3& T_cw, const std::vector<Eigen::Vector3d>& points_w,
                 const std::vector<Eigen::Vector2d>& pixels, const core::PinholeCamera& camera, double threshold2) {
  int count = 0;
  for (size_t i = 0; i < points_w.size(); ++i)
    count += squaredError(T_cw, points_w[i], pixels[i], camera) < threshold2 ? 1 : 0;
  return count;
}

// k distinct indices in [0, n). Uses the raw mt19937 output (fully specified by the standard) rather than
// std::uniform_int_distribution (implementation-defined), so a seed gives the same samples on every platform.
std::array<int, kMaxSampleSize> sampleIndices(std::mt19937& rng, int n, int sample_size) {
  std::array<int, kMaxSampleSize> idx{};
  for (int k = 0; k < sample_size; ++k) {
    bool fresh = false;
    while (!fresh) {
      idx[k] = static_cast<int>(rng() % static_cast<std::uint32_t>(n));
      fresh = std::find(idx.begin(), idx.begin() + k, idx[k]) == idx.begin() + k;
    }
  }
  return idx;
}

// Gauss-Newton with a small Levenberg damping on the reprojection error of `subset`, perturbing on the left
// (core/pose.h convention): d(p_c)/d[rho, phi] = [I, -[p_c]x].
core::SE3 refinePose(core::SE3 T_cw, const std::vector<Eigen::Vector3d>& points_w,
                     const std::vector<Eigen::Vector2d>& pixels, const core::PinholeCamera& camera,
                     const std::vector<int>& subset, int max_iterations = kRefineIterations) {
  const double fx = camera.fx(), fy = camera.fy();
  auto cost = [&](const core::SE3& T) {
    double c = 0;
    for (int i : subset) c += std::min(squaredError(T, points_w[i], pixels[i], camera), 1e12);
    return c;
  };
  double current = cost(T_cw);
  double lambda = 1e-4;
  for (int it = 0; it < max_iterations; ++it) {
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    core::Vector6d g = core::Vector6d::Zero();
    for (int i : subset) {
      const Eigen::Vector3d p = T_cw * points_w[i];
      if (p.z() <= 1e-9) continue;
      const double iz = 1.0 / p.z(), iz2 = iz * iz;
      Eigen::Matrix<double, 2, 3> J_proj;
      J_proj << fx * iz, 0, -fx * p.x() * iz2, 0, fy * iz, -fy * p.y() * iz2;
      Eigen::Matrix<double, 3, 6> J_pose;
      J_pose.leftCols<3>().setIdentity();
      J_pose.rightCols<3>() = -core::skew(p);
      const Eigen::Matrix<double, 2, 6> J = J_proj * J_pose;
      const Eigen::Vector2d r = camera.project(p) - pixels[i];
      H.noalias() += J.transpose() * J;
      g.noalias() += J.transpose() * r;
    }
    bool improved = false;
    while (!improved && lambda < 1e8) {
      Eigen::Matrix<double, 6, 6> A = H;
      A.diagonal() *= 1.0 + lambda;
      const core::Vector6d delta = A.ldlt().solve(-g);
      if (!delta.allFinite()) break;
      const core::SE3 candidate = core::expSE3(delta) * T_cw;
      const double c = cost(candidate);
      if (c < current) {
        const double gain = current - c;
        T_cw = candidate;
        current = c;
        lambda = std::max(lambda * 0.1, 1e-9);
        improved = true;
        if (gain < 1e-10 * (1 + current) || delta.norm() < 1e-12) return T_cw;
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;
  }
  return T_cw;
}

// What ap3pPoses needs between samples: OpenCV returns the poses in matrices, kept here across the samples of one
// RANSAC so that a sample allocates nothing once they have their size.
struct P3pBuffers {
  std::vector<cv::Mat> rvecs, tvecs;
};

// AP3P's up to four poses from three correspondences (normalised coordinates, so the camera matrix is the
// identity). Degenerate samples (collinear points) give none.
void ap3pPoses(const std::vector<Eigen::Vector3d>& sample_w, const std::vector<Eigen::Vector2d>& sample_xy,
               P3pBuffers& buffers, std::vector<core::SE3>& poses) {
  // One point per row (3x3 and 3x2 single-channel, as solveP3P accepts them), on the stack.
  cv::Matx33d object;
  cv::Matx32d image;
  for (int k = 0; k < kP3pSampleSize; ++k) {
    for (int c = 0; c < 3; ++c) object(k, c) = sample_w[k][c];
    for (int c = 0; c < 2; ++c) image(k, c) = sample_xy[k][c];
  }
  int found = 0;
  try {
    found = cv::solveP3P(object, image, cv::Matx33d::eye(), cv::noArray(), buffers.rvecs, buffers.tvecs,
                         cv::SOLVEPNP_AP3P);
  } catch (const cv::Exception&) {
    return;  // a degenerate sample: no hypothesis
  }
  for (int s = 0; s < found; ++s) {
    cv::Matx33d R;
    cv::Rodrigues(buffers.rvecs[s], R);
    const cv::Vec3d t(buffers.tvecs[s]);
    Eigen::Matrix3d R_e;
    cv::cv2eigen(R, R_e);
    core::SE3 T = core::SE3::Identity();
    T.linear() = R_e;
    T.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
    if (T.matrix().allFinite()) poses.push_back(T);
  }
}

void hypothesesFromSample(PnpMinimalSolver solver, const std::vector<Eigen::Vector3d>& sample_w,
                          const std::vector<Eigen::Vector2d>& sample_xy, P3pBuffers& buffers,
                          std::vector<core::SE3>& poses) {
  poses.clear();
  if (solver == PnpMinimalSolver::kAp3p) {
    ap3pPoses(sample_w, sample_xy, buffers, poses);
  } else if (const std::optional<core::SE3> T = solveEpnp(sample_w, sample_xy)) {
    poses.push_back(*T);
  }
}

}  // namespace

int countCoveredCells(const std::vector<Eigen::Vector2d>& pixels, const std::vector<int>& indices, double width,
                      double height, int cols, int rows) {
  std::vector<char> hit(static_cast<std::size_t>(std::max(0, cols * rows)), 0);
  for (const int i : indices) {
    const int cx = std::clamp(static_cast<int>(pixels[i].x() * cols / width), 0, cols - 1);
    const int cy = std::clamp(static_cast<int>(pixels[i].y() * rows / height), 0, rows - 1);
    hit[static_cast<std::size_t>(cy * cols + cx)] = 1;
  }
  return static_cast<int>(std::count(hit.begin(), hit.end(), 1));
}

PnpResult solvePnpRansac(const std::vector<Eigen::Vector3d>& points_w, const std::vector<Eigen::Vector2d>& pixels,
                         const core::PinholeCamera& camera, const PnpRansacOptions& options) {
  options.check();
  core::require(points_w.size() == pixels.size(),
                fmt::format("solvePnpRansac: {} points but {} pixels", points_w.size(), pixels.size()));
  PnpResult result;
  const int n = static_cast<int>(points_w.size());
  const int sample_size = options.minimal_solver == PnpMinimalSolver::kAp3p ? kP3pSampleSize : kEpnpSampleSize;
  if (n < std::max(sample_size, options.min_inliers)) return result;

  const double threshold2 = options.reprojection_threshold_px * options.reprojection_threshold_px;
  std::mt19937 rng(options.seed);
  // The minimal solvers work on normalised image coordinates.
  std::vector<Eigen::Vector2d> normalized(pixels.size());
  for (size_t i = 0; i < pixels.size(); ++i)
    normalized[i] = {(pixels[i].x() - camera.cx()) / camera.fx(), (pixels[i].y() - camera.cy()) / camera.fy()};
  std::vector<Eigen::Vector3d> sample_w(sample_size);
  std::vector<Eigen::Vector2d> sample_xy(sample_size);
  std::vector<core::SE3> hypotheses;
  P3pBuffers p3p_buffers;
  std::vector<int> support;

  // LO-RANSAC over the minimal solver's hypotheses; the iteration budget shrinks as the best inlier ratio grows
  // (confidence). With the coverage ranking a second best is kept: the hypothesis whose inliers reach the most
  // cells; it is returned when its support is at least coverage_min_support times the largest.
  struct Best {
    core::SE3 T = core::SE3::Identity();
    int count = 0, cells = 0;
  };
  Best by_count, by_cells;
  const bool by_coverage = options.coverage_cols > 0 && options.coverage_rows > 0;
  auto coveredCells = [&](const std::vector<int>& inliers) {
    return countCoveredCells(pixels, inliers, camera.intrinsics().width, camera.intrinsics().height,
                             options.coverage_cols, options.coverage_rows);
  };
  // Whether a support clears the floor (it only rises, as by_count grows: what falls below it stays below), and
  // whether a hypothesis is wider than by_cells (which no longer counts once it has fallen below the floor).
  auto eligible = [&](int count) { return count > 0 && count >= options.coverage_min_support * by_count.count; };
  auto wider = [&](int cells, int count) {
    if (!eligible(by_cells.count)) return true;
    return cells > by_cells.cells || (cells == by_cells.cells && count > by_cells.count);
  };
  int budget = options.max_iterations;
  for (int it = 0; it < budget; ++it) {
    const auto idx = sampleIndices(rng, n, sample_size);
    for (int k = 0; k < sample_size; ++k) {
      sample_w[k] = points_w[idx[k]];
      sample_xy[k] = normalized[idx[k]];
    }
    hypothesesFromSample(options.minimal_solver, sample_w, sample_xy, p3p_buffers, hypotheses);
    for (const core::SE3& T : hypotheses) {
      int count = countInliers(T, points_w, pixels, camera, threshold2);
      int cells = 0;
      bool is_wider = false;
      if (by_coverage && count >= sample_size + 1 && eligible(count)) {
        collectInliers(T, points_w, pixels, camera, threshold2, support);
        cells = coveredCells(support);
        is_wider = wider(cells, count);
      }
      if (count <= by_count.count && !is_wider) continue;
      core::SE3 T_best = T;
      // Local optimisation (LO-RANSAC, Chum et al. 2003): a hypothesis from a few noisy points underestimates its
      // support; refitting it to its inliers recovers the true inlier ratio, so the budget below shrinks as it
      // should and the final refinement starts closer.
      if (count >= sample_size + 1) {
        if (!by_coverage) collectInliers(T_best, points_w, pixels, camera, threshold2, support);  // else it holds them
        const core::SE3 T_lo = refinePose(T_best, points_w, pixels, camera, support, kLocalRefineIterations);
        if (by_coverage) {
          std::vector<int> support_lo;
          collectInliers(T_lo, points_w, pixels, camera, threshold2, support_lo);
          const Best refit{T_lo, static_cast<int>(support_lo.size()), coveredCells(support_lo)};
          // Each ranking keeps whichever of the hypothesis and its refit it prefers (the hypothesis on ties).
          for (const Best& b : {Best{T, count, cells}, refit})
            if (b.count > by_count.count) by_count = b;
          for (const Best& b : {Best{T, count, cells}, refit})
            if (eligible(b.count) && wider(b.cells, b.count)) by_cells = b;
        } else {
          const int count_lo = countInliers(T_lo, points_w, pixels, camera, threshold2);
          if (count_lo > count) {
            count = count_lo;
            T_best = T_lo;
          }
        }
      } else if (by_coverage && count > by_count.count) {
        by_count = {T, count, 0};  // too little support to refit, or to rank by cells
      }
      if (!by_coverage) by_count = {T_best, count, 0};
      // The budget follows the best hypothesis's support (the widest one's under the coverage ranking: drawing
      // until an all-inlier sample of it is likely).
      const int leading = by_coverage && eligible(by_cells.count) ? by_cells.count : by_count.count;
      const double w = static_cast<double>(leading) / n;
      const double p_all_inliers = std::pow(w, sample_size);
      if (p_all_inliers >= 1.0 - 1e-12) {
        budget = it + 1;
      } else if (p_all_inliers > 0) {
        const double needed = std::log(1.0 - options.confidence) / std::log(1.0 - p_all_inliers);
        // Compare in double: `needed` overflows int when the inlier ratio is tiny.
        budget = static_cast<int>(std::min<double>(options.max_iterations, std::ceil(needed)));
      }
    }
  }
  const bool take_cells = by_coverage && eligible(by_cells.count);
  const core::SE3 best_T = take_cells ? by_cells.T : by_count.T;
  const int best_count = take_cells ? by_cells.count : by_count.count;
  if (best_count < std::max(kMinSupport, options.min_inliers)) return result;

  // Refine on the inliers, then re-evaluate them with the refined pose, until the set is stable.
  std::vector<int> inliers;
  collectInliers(best_T, points_w, pixels, camera, threshold2, inliers);
  core::SE3 T = best_T;
  for (int round = 0; round < kInlierRounds; ++round) {
    T = refinePose(T, points_w, pixels, camera, inliers);
    std::vector<int> refreshed;
    collectInliers(T, points_w, pixels, camera, threshold2, refreshed);
    const bool stable = refreshed == inliers;
    inliers = std::move(refreshed);
    if (stable || static_cast<int>(inliers.size()) < options.min_inliers) break;
  }

  result.T_cw = T;
  result.inliers = std::move(inliers);
  result.success = static_cast<int>(result.inliers.size()) >= options.min_inliers;
  return result;
}

}  // namespace amos::geometry
