#include "amos/evidence/baseline_tracks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <opencv2/video/tracking.hpp>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/dynamic/frame_regions.h"
#include "amos/dynamic/robust_scale.h"

namespace amos::evidence {

using namespace dynamic;  // NOLINT(google-build-using-namespace): the front end's types

namespace {

// Per label of a CV_32S map (count labels), the points that lie on it and those of them that move.
struct LabelVotes {
  std::vector<int> moving, all;
};
LabelVotes votesPerLabel(const BaselineMotion& motion, const cv::Mat& labels, int count) {
  LabelVotes votes{std::vector<int>(count, 0), std::vector<int>(count, 0)};
  for (const BaselinePoint& p : motion.points) {
    const int label = labelAt(labels, p.current);
    if (label < 0 || label >= count) continue;
    ++votes.all[label];
    votes.moving[label] += p.moving;
  }
  return votes;
}

// Whether the LK window around p (radius px) holds a hole or a depth step of more than ratio of p's depth: at an
// occlusion edge the far side shifts against the near one by the parallax of the whole baseline, which reads as
// motion of the window.
bool windowOnDepthEdge(const cv::Mat& depth, cv::Point2f p, int radius, double ratio) {
  const int u = static_cast<int>(std::lround(p.x)), v = static_cast<int>(std::lround(p.y));
  if (u < radius || v < radius || u >= depth.cols - radius || v >= depth.rows - radius) return true;
  const float z = depth.at<float>(v, u);
  const float tolerance = static_cast<float>(ratio) * z;
  for (int dv = -radius; dv <= radius; ++dv) {
    const float* row = depth.ptr<float>(v + dv);
    for (int du = -radius; du <= radius; ++du) {
      const float zn = row[u + du];
      if (!(zn > 0.f) || std::abs(zn - z) > tolerance) return true;
    }
  }
  return false;
}

}  // namespace

BaselineMotion baselineMotion(const std::vector<cv::Point2f>& points, const BaselineImages& frames,
                              const core::PinholeCamera& camera, const DynamicOptions& options) {
  const cv::Mat& gray = frames.gray;
  const cv::Mat& baseline_gray = frames.baseline_gray;
  core::require(gray.type() == CV_8UC1 && baseline_gray.type() == CV_8UC1 && gray.size() == baseline_gray.size(),
                "baselineMotion: both images must be CV_8UC1 of one size");
  const ImagePyramid pyramid = buildPyramid(gray, options.tracking);
  const ImagePyramid baseline_pyramid = buildPyramid(baseline_gray, options.tracking);
  const BaselinePyramids pyramids{pyramid, frames.depth, frames.T_cw, baseline_pyramid, frames.T_cw_baseline};
  return baselineMotion(points, pyramids, camera, options);
}

namespace {

// A point followed from the current frame into the baseline frame, with its residual against the static world's
// prediction (undistorted pixels), before the common shift is removed.
struct FollowedPoint {
  cv::Point2f current, found;
  Eigen::Vector2d residual;
};

// Steps 1 and 2 of the header for `points`, and their residuals.
std::vector<FollowedPoint> followIntoBaseline(const std::vector<cv::Point2f>& points, const BaselinePyramids& frames,
                                              const core::PinholeCamera& camera, const CornerTrackingOptions& lk,
                                              const ReprojectionOptions& reprojection) {
  const ImagePyramid& pyramid = frames.pyramid;
  const ImagePyramid& baseline_pyramid = frames.baseline_pyramid;
  const cv::Mat& depth = frames.depth;
  const core::SE3& T_cw = frames.T_cw;
  const core::SE3& T_cw_baseline = frames.T_cw_baseline;
  const cv::Mat& gray = pyramid.front();
  std::vector<FollowedPoint> out;
  // 1. The static world's prediction: lifted with the current depth, projected into the baseline frame.
  std::vector<PointTrack> lifted(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) lifted[i].last = points[i];
  const std::vector<std::optional<Eigen::Vector3d>> points_w =
      backProjectTracks(lifted, depth, T_cw, camera, reprojection);
  std::vector<cv::Point2f> from, predicted_undistorted;
  std::vector<Eigen::Vector3d> world;
  const int window_radius = lk.lk_window / 2;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points_w[i] || windowOnDepthEdge(depth, points[i], window_radius, reprojection.depth_edge_ratio)) continue;
    const Eigen::Vector3d p_b = T_cw_baseline * *points_w[i];
    if (p_b.z() < 1e-6) continue;
    const Eigen::Vector2d uv = camera.project(p_b);
    predicted_undistorted.emplace_back(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
    from.push_back(points[i]);
    world.push_back(*points_w[i]);
  }
  if (from.empty()) return out;
  const std::vector<cv::Point2f> predicted = camera.distort(predicted_undistorted);
  // 2. LK into the baseline image from the prediction; back again from where it ended, with the same offset, so
  // that only a point consistent both ways returns.
  const float margin = static_cast<float>(lk.lk_window / 2 + 1);
  const cv::Rect2f inside(margin, margin, static_cast<float>(gray.cols) - 2 * margin,
                          static_cast<float>(gray.rows) - 2 * margin);
  std::vector<cv::Point2f> start, guess;
  std::vector<Eigen::Vector3d> start_world;
  for (std::size_t k = 0; k < from.size(); ++k) {
    if (!inside.contains(predicted[k])) continue;
    start.push_back(from[k]);
    guess.push_back(predicted[k]);
    start_world.push_back(world[k]);
  }
  if (start.empty()) return out;
  // All of Dynamic.LK.pyramidLevels: with two (20 px of reach from the prediction) walking_rpy seed 4 went from
  // 1.41x to 1.66x its static twin (a walker the pose half followed moves more than that over ten frames).
  const cv::Size window(lk.lk_window, lk.lk_window);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, lk.lk_max_iterations, lk.lk_epsilon);
  std::vector<cv::Point2f> found = guess;
  std::vector<uchar> ok_forward, ok_backward;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(pyramid, baseline_pyramid, start, found, ok_forward, error, window, lk.lk_levels, stop,
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  std::vector<cv::Point2f> back(found.size());
  for (std::size_t k = 0; k < found.size(); ++k) back[k] = found[k] + (start[k] - guess[k]);
  cv::calcOpticalFlowPyrLK(baseline_pyramid, pyramid, found, back, ok_backward, error, window, lk.lk_levels, stop,
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  const float fb2 = static_cast<float>(lk.forward_backward_px * lk.forward_backward_px);
  const cv::Rect2f image(0.f, 0.f, static_cast<float>(gray.cols - 1), static_cast<float>(gray.rows - 1));
  std::vector<PointTrack> tracks;  // current frame ("last") -> baseline frame ("current")
  std::vector<std::optional<Eigen::Vector3d>> tracked_w;
  for (std::size_t k = 0; k < start.size(); ++k) {
    if (!ok_forward[k] || !ok_backward[k] || !image.contains(found[k])) continue;
    const cv::Point2f d = back[k] - start[k];
    if (d.dot(d) > fb2) continue;
    tracks.push_back({start[k], found[k], static_cast<int>(k)});
    tracked_w.push_back(start_world[k]);
  }
  const std::vector<std::optional<Eigen::Vector2d>> residuals =
      reprojectionResiduals(tracks, tracked_w, T_cw_baseline, camera);
  for (std::size_t k = 0; k < tracks.size(); ++k)
    if (residuals[k]) out.push_back({tracks[k].last, tracks[k].current, *residuals[k]});
  return out;
}

// Step 4 for followed points, against the common shift and bar of `motion`, appended to it.
void classifyInto(const std::vector<FollowedPoint>& followed, BaselineMotion& motion) {
  motion.points.reserve(motion.points.size() + followed.size());
  for (const FollowedPoint& f : followed) {
    BaselinePoint p;
    p.current = f.current;
    p.found = f.found;
    p.residual_px = (f.residual - motion.shift_px).norm();
    p.moving = p.residual_px > motion.bar_px;
    motion.moving_points += p.moving;
    motion.points.push_back(p);
  }
}

}  // namespace

WindowStructure windowStructure(const cv::Mat& gray, int u, int v) {
  WindowStructure w;
  for (int dv = -3; dv <= 3; ++dv) {
    const std::uint8_t* row = gray.ptr<std::uint8_t>(v + dv);
    const std::uint8_t* up = gray.ptr<std::uint8_t>(v + dv - 1);
    const std::uint8_t* down = gray.ptr<std::uint8_t>(v + dv + 1);
    for (int du = -3; du <= 3; ++du) {
      const int x = u + du;
      const double gx = 0.5 * (row[x + 1] - row[x - 1]), gy = 0.5 * (down[x] - up[x]);
      w.xx += gx * gx, w.xy += gx * gy, w.yy += gy * gy;
    }
  }
  w.xx /= 49, w.xy /= 49, w.yy /= 49;
  return w;
}

BaselineMotion baselineMotion(const std::vector<cv::Point2f>& points, const BaselinePyramids& frames,
                              const core::PinholeCamera& camera, const DynamicOptions& all_options) {
  const ImagePyramid& pyramid = frames.pyramid;
  const ImagePyramid& baseline_pyramid = frames.baseline_pyramid;
  const cv::Mat& depth = frames.depth;
  const CornerTrackingOptions& lk = all_options.tracking;
  const ReprojectionOptions& reprojection = all_options.reprojection;
  const BaselineTrackOptions& options = all_options.baseline_tracks;
  options.check();
  core::require(!pyramid.empty() && !baseline_pyramid.empty() && pyramid.front().size() == baseline_pyramid.front().size(),
                "baselineMotion: both pyramids must be built, from images of one size");
  core::require(depth.type() == CV_32F && depth.size() == pyramid.front().size(),
                "baselineMotion: depth must be CV_32F metres of the image size");
  BaselineMotion out;
  const std::vector<FollowedPoint> followed = followIntoBaseline(points, frames, camera, lk, reprojection);
  // 3. What the two tracked poses' relative error does to every point alike: the median residual (a small rotation
  // error shifts the image nearly uniformly, ~1 px per 0.1 deg), and the points' noise around it. Not a 6-DoF pose
  // refit: where the scene is two planes (a door and its wall) a translation and a rotation together explain a
  // mover's sideways shift exactly, and a refit would absorb it.
  out.ok = static_cast<int>(followed.size()) >= reprojection.refit_min_points;
  if (!out.ok) return out;
  std::vector<double> rx, ry;
  for (const FollowedPoint& f : followed) rx.push_back(f.residual.x()), ry.push_back(f.residual.y());
  out.shift_px = Eigen::Vector2d(upperMedian(std::move(rx)), upperMedian(std::move(ry)));
  std::vector<double> norms;
  for (const FollowedPoint& f : followed) norms.push_back((f.residual - out.shift_px).norm());
  out.sigma_px = pixelNoiseScale(std::move(norms));  // as refitPose
  out.bar_px = std::max(options.min_motion_px, options.sigmas * out.sigma_px);
  // 4. Moving: beyond the bar around the common shift.
  classifyInto(followed, out);
  return out;
}

std::vector<bool> baselineMovingSuperpixels(const BaselineMotion& motion, const cv::Mat& labels, int count,
                                            const BaselineTrackOptions& options) {
  core::require(labels.type() == CV_32S, "baselineMovingSuperpixels: labels must be CV_32S");
  const LabelVotes votes = votesPerLabel(motion, labels, count);
  std::vector<bool> out(count, false);
  for (int s = 0; s < count; ++s) {
    const int moving = votes.moving[s], still = votes.all[s] - moving;
    out[s] = moving >= options.min_votes && moving > still;
  }
  return out;
}

std::vector<int> baselinePointsPerSuperpixel(const BaselineMotion& motion, const cv::Mat& labels, int count) {
  core::require(labels.type() == CV_32S, "baselinePointsPerSuperpixel: labels must be CV_32S");
  return votesPerLabel(motion, labels, count).all;
}

std::vector<bool> baselineMovingClusters(const BaselineMotion& motion, const cv::Mat& decision_map, int num_clusters,
                                         const BaselineTrackOptions& options) {
  core::require(decision_map.type() == CV_32S, "baselineMovingClusters: the decision map must be CV_32S");
  const LabelVotes votes = votesPerLabel(motion, decision_map, num_clusters);
  std::vector<bool> out(num_clusters, false);
  for (int c = 0; c < num_clusters; ++c)
    out[c] = votes.moving[c] >= options.min_votes && votes.moving[c] >= options.cluster_share * votes.all[c];
  return out;
}

}  // namespace amos::evidence
