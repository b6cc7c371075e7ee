#include "amos/dynamic/corner_tracking.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::dynamic {

void CornerTrackingOptions::check() const {
  core::requireAtLeast(max_corners, "max_corners", 8);
  core::requireOption(quality_level > 0 && quality_level < 1, core::option(quality_level, "quality_level"),
                      fmt::format("must lie in (0, 1), got {}", quality_level));
  core::requireAtLeast(min_distance_px, "min_distance_px", 0);
  core::requireOption(detection_scale > 0 && detection_scale <= 1, core::option(detection_scale, "detection_scale"),
                      fmt::format("must lie in (0, 1], got {}", detection_scale));
  core::requireOption(lk_window >= 5 && lk_window % 2 == 1, core::option(lk_window, "lk_window"),
                      fmt::format("must be an odd number >= 5, got {}", lk_window));
  core::requireOption(lk_levels >= 0 && lk_levels <= 6, core::option(lk_levels, "lk_levels"),
                      fmt::format("must lie in [0, 6], got {}", lk_levels));
  core::requireAtLeast(lk_max_iterations, "lk_max_iterations", 1);
  core::requirePositive(lk_epsilon, "lk_epsilon");
  core::requirePositive(forward_backward_px, "forward_backward_px");
}

ImagePyramid buildPyramid(const cv::Mat& gray, const CornerTrackingOptions& options) {
  options.check();
  core::require(!gray.empty() && gray.type() == CV_8UC1, "buildPyramid: the image must be a non-empty CV_8UC1");
  ImagePyramid pyramid;
  cv::buildOpticalFlowPyramid(gray, pyramid, cv::Size(options.lk_window, options.lk_window), options.lk_levels);
  return pyramid;
}

FramePairPyramids buildPyramids(const cv::Mat& last_gray, const cv::Mat& current_gray,
                                const CornerTrackingOptions& options) {
  core::require(!last_gray.empty() && last_gray.type() == CV_8UC1 && current_gray.type() == CV_8UC1 &&
                    last_gray.size() == current_gray.size(),
                "buildPyramids: both images must be CV_8UC1 of the same size");
  return {buildPyramid(last_gray, options), buildPyramid(current_gray, options)};
}

std::vector<PointTrack> trackPoints(const FramePairPyramids& pyramids, const std::vector<cv::Point2f>& points,
                                    const CornerTrackingOptions& options) {
  options.check();
  core::require(!pyramids.last.empty() && !pyramids.current.empty(), "trackPoints: pyramids are empty");
  std::vector<PointTrack> tracks;
  if (points.empty()) return tracks;
  const cv::Size window(options.lk_window, options.lk_window);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, options.lk_max_iterations,
                              options.lk_epsilon);
  std::vector<cv::Point2f> forward;
  std::vector<uchar> ok_forward;
  // No error output: nothing reads it, and without it OpenCV skips a pass over every window at full resolution
  // (the tracks and their status do not depend on it).
  cv::calcOpticalFlowPyrLK(pyramids.last, pyramids.current, points, forward, ok_forward, cv::noArray(), window,
                           options.lk_levels, stop);
  // Only the points that converged inside the image go back (LK treats every point on its own, so leaving the
  // others out changes nothing for these). The backward pass starts where the forward pass ended, without a hint
  // towards the original point, so that only a track consistent in both directions returns to it.
  const cv::Size size = pyramids.current.front().size();
  const cv::Rect2f inside(0.f, 0.f, static_cast<float>(size.width - 1), static_cast<float>(size.height - 1));
  std::vector<int> candidates;
  std::vector<cv::Point2f> returning;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!ok_forward[i] || !inside.contains(forward[i])) continue;
    candidates.push_back(static_cast<int>(i));
    returning.push_back(forward[i]);
  }
  if (candidates.empty()) return tracks;
  if (!options.forward_backward_check) {
    for (int i : candidates)
      tracks.push_back({points[static_cast<std::size_t>(i)], forward[static_cast<std::size_t>(i)], i});
    return tracks;
  }
  std::vector<cv::Point2f> backward;
  std::vector<uchar> ok_backward;
  cv::calcOpticalFlowPyrLK(pyramids.current, pyramids.last, returning, backward, ok_backward, cv::noArray(), window,
                           options.lk_levels, stop);
  const float fb2 = static_cast<float>(options.forward_backward_px * options.forward_backward_px);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (!ok_backward[k]) continue;
    const int i = candidates[k];
    const cv::Point2f d = backward[k] - points[static_cast<std::size_t>(i)];
    if (d.dot(d) > fb2) continue;
    tracks.push_back({points[static_cast<std::size_t>(i)], forward[static_cast<std::size_t>(i)], i});
  }
  return tracks;
}

std::vector<PointTrack> trackCorners(const cv::Mat& last_gray, const cv::Mat& current_gray,
                                     const CornerTrackingOptions& options, const cv::Mat& mask) {
  return trackCorners(last_gray, buildPyramids(last_gray, current_gray, options), options, mask);
}

std::vector<PointTrack> trackCorners(const cv::Mat& last_gray, const FramePairPyramids& pyramids,
                                     const CornerTrackingOptions& options, const cv::Mat& mask) {
  core::require(!last_gray.empty() && !pyramids.last.empty() && pyramids.last.front().size() == last_gray.size(),
                "trackCorners: the last frame's pyramid does not belong to its image");
  return trackPoints(pyramids, detectCorners(last_gray, options, mask), options);
}

std::vector<cv::Point2f> detectCorners(const cv::Mat& gray, const CornerTrackingOptions& options, const cv::Mat& mask) {
  options.check();
  core::require(!gray.empty() && gray.type() == CV_8UC1, "detectCorners: the image must be a non-empty CV_8UC1");
  core::require(mask.empty() || (mask.type() == CV_8UC1 && mask.size() == gray.size()),
                "detectCorners: the mask must be empty or CV_8UC1 of the image size");
  std::vector<cv::Point2f> corners;
  if (options.detection_scale < 1.0) {
    const double s = options.detection_scale;
    cv::Mat small, small_mask;
    cv::resize(gray, small, cv::Size(), s, s, cv::INTER_AREA);
    if (!mask.empty()) cv::resize(mask, small_mask, small.size(), 0, 0, cv::INTER_NEAREST);
    cv::goodFeaturesToTrack(small, corners, options.max_corners, options.quality_level, options.min_distance_px * s,
                            small_mask);
    // Pixel centres: small (x + 0.5) / s - 0.5 in the full image.
    for (cv::Point2f& c : corners)
      c = cv::Point2f(static_cast<float>((c.x + 0.5) / s - 0.5), static_cast<float>((c.y + 0.5) / s - 0.5));
  } else {
    cv::goodFeaturesToTrack(gray, corners, options.max_corners, options.quality_level, options.min_distance_px, mask);
  }
  return corners;
}

}  // namespace amos::dynamic
