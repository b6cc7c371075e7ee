#include "amos/dynamic/rigid_mover_depth.h"

#include <cmath>
#include <optional>

#include "amos/core/error.h"
#include "amos/dynamic/frame_regions.h"

namespace amos::dynamic {

namespace {

// The current depth's residual at the raw pixel a hypothesis puts a point of depth z: measured minus predicted
// (positive: the current frame sees beyond the point). Empty where the pixel leaves the image or its depth is
// missing, on an edge or beyond the range (smoothDepthAt).
std::optional<double> residualAt(const cv::Mat& depth, const cv::Point2f& at, double z, double depth_edge_ratio,
                                 const DepthEvidenceOptions& options) {
  const float measured = smoothDepthAt(depth, cvRound(at.x), cvRound(at.y), depth_edge_ratio);
  if (measured <= 0.f || measured > options.max_depth_m) return std::nullopt;
  return measured - z;
}

}  // namespace

std::vector<RigidSampleVote> rigidMoverDepthVotes(const std::vector<RigidMover>& movers, const core::SE3& T_bc_static,
                                                  const cv::Mat& depth, const cv::Mat& baseline_depth,
                                                  const core::PinholeCamera& camera, const DepthSampleGrid& grid,
                                                  const cv::Mat& labels, int count, int reach_px,
                                                  double depth_edge_ratio, const DepthEvidenceOptions& depth_options) {
  core::require(depth.type() == CV_32F && baseline_depth.type() == CV_32F && labels.type() == CV_32S &&
                    depth.size() == baseline_depth.size() && depth.size() == labels.size() &&
                    depth.cols == camera.width() && depth.rows == camera.height(),
                "rigidMoverDepthVotes: depths CV_32F and labels CV_32S of the camera's size");
  std::vector<RigidSampleVote> out;
  if (movers.empty()) return out;

  // Per hypothesis (0: the static world, 1 + m: mover m), baseline camera -> current camera.
  std::vector<core::SE3> T_cb{T_bc_static.inverse()};
  for (const RigidMover& m : movers) T_cb.push_back(m.T_bc.inverse());
  const std::size_t hypotheses = T_cb.size();

  // The baseline samples, lifted, and their pixels (undistorted, then raw) and depths in the current camera per
  // hypothesis.
  std::vector<std::vector<cv::Point2f>> ideal(hypotheses);
  std::vector<std::vector<double>> z(hypotheses);
  for (std::size_t i = 0; i < grid.pixels().size(); ++i) {
    const cv::Point q = grid.pixels()[i];
    const float zb = smoothDepthAt(baseline_depth, q.x, q.y, depth_edge_ratio);
    if (zb <= 0.f || zb > depth_options.max_depth_m) continue;
    const cv::Point2d& xn = grid.normalised()[i];
    const Eigen::Vector3d X_b(xn.x * zb, xn.y * zb, zb);
    for (std::size_t h = 0; h < hypotheses; ++h) {
      const Eigen::Vector3d X = T_cb[h] * X_b;
      const bool in_front = X.z() > 0.1;
      const Eigen::Vector2d uv = in_front ? camera.project(X) : Eigen::Vector2d(-1e6, -1e6);
      ideal[h].emplace_back(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
      z[h].push_back(in_front ? X.z() : -1.0);
    }
  }
  std::vector<std::vector<cv::Point2f>> pixel(hypotheses);
  for (std::size_t h = 0; h < hypotheses; ++h) pixel[h] = camera.distort(ideal[h]);

  const double sigmas = depth_options.violation_sigmas * std::sqrt(2.0);  // two measurements of the noise
  auto supports = [&](double r, double zp) {
    return std::abs(r) <= std::max({sigmas * depth_options.sigma(zp), depth_options.min_residual_m,
                                    depth_options.min_relative_residual * zp});
  };
  auto refutes = [&](double r, double zp) {
    return r > std::max({sigmas * depth_options.sigma(zp), depth_options.min_residual_m,
                         depth_options.baseline_relative_residual * zp});
  };
  // A vote for a mover lands on the current pixel where the mover's motion puts the sample; it counts only if the
  // static world does not explain that pixel the other way round (its current point, moved into the baseline camera,
  // matches the depth seen there): a motion fitted a little wrong may carry a box's top edge onto the desk front
  // behind it, at nearly the same depth, and the desk front is static.
  struct Candidate {
    int superpixel, mover;
    Eigen::Vector3d X_c;  // the current frame's point at that pixel
  };
  std::vector<Candidate> candidates;
  const float reach = static_cast<float>(reach_px);
  const std::size_t n = z[0].size();
  for (std::size_t i = 0; i < n; ++i) {
    if (z[0][i] <= 0) continue;
    const std::optional<double> r_static = residualAt(depth, pixel[0][i], z[0][i], depth_edge_ratio, depth_options);
    if (!r_static) continue;
    const bool static_supported = supports(*r_static, z[0][i]), static_refuted = refutes(*r_static, z[0][i]);
    if (!static_supported && !static_refuted) continue;  // hidden, or between the bars: no evidence either way
    for (std::size_t h = 1; h < hypotheses; ++h) {
      if (z[h][i] <= 0) continue;
      const int m = static_cast<int>(h) - 1;
      const cv::Point2f& at = static_refuted ? pixel[h][i] : pixel[0][i];  // where the vote is counted
      if (!withinReach(movers[h - 1].region, at, reach)) continue;
      const std::optional<double> r_mover = residualAt(depth, pixel[h][i], z[h][i], depth_edge_ratio, depth_options);
      if (!r_mover) continue;
      const int s = labelAt(labels, at);
      if (s < 0 || s >= count) continue;
      if (static_refuted && supports(*r_mover, z[h][i])) {
        const double measured = z[h][i] + *r_mover;
        candidates.push_back({s, m, camera.backProject(ideal[h][i].x, ideal[h][i].y, measured)});
        break;
      }
      if (static_supported && refutes(*r_mover, z[h][i])) {
        out.push_back({s, -1 - m});
        break;
      }
    }
  }
  std::vector<cv::Point2f> back(candidates.size());
  std::vector<double> back_z(candidates.size(), -1.0);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Eigen::Vector3d X_b = T_bc_static * candidates[k].X_c;
    if (X_b.z() <= 0.1) continue;
    const Eigen::Vector2d uv = camera.project(X_b);
    back[k] = cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
    back_z[k] = X_b.z();
  }
  back = camera.distort(back);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (back_z[k] > 0) {
      const std::optional<double> r = residualAt(baseline_depth, back[k], back_z[k], depth_edge_ratio, depth_options);
      if (r && supports(*r, back_z[k])) continue;  // the static world explains the pixel
    }
    out.push_back({candidates[k].superpixel, candidates[k].mover});
  }
  return out;
}

}  // namespace amos::dynamic
