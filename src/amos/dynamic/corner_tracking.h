#pragma once
// Sparse correspondences between the last and the current frame (paper III-C: "corner points are extracted
// from the last frame and tracked through the LK optical flow"): Shi-Tomasi corners, pyramidal Lucas-Kanade,
// and a forward-backward check that drops tracks which do not return to where they started.
#include <opencv2/core.hpp>

#include <vector>

namespace amos::dynamic {

struct CornerTrackingOptions {
  // Dynamic.Corners.maxCorners: 16 clusters need ~10+ tracks each to score; 500 leaves room for the ~30% that
  // fall without depth or fail the checks, and LK on 500 points costs a few ms.
  int max_corners = 500;
  // Dynamic.Corners.qualityLevel: Shi-Tomasi response relative to the best corner (OpenCV's usual 0.01).
  double quality_level = 0.01;
  // Dynamic.Corners.minDistance: 10 px spreads the corners over the image (~one per 10x10 px cell at most).
  double min_distance_px = 10.0;
  // Dynamic.LK.window: 21x21 px window, OpenCV's default; large enough for the 1-3 px/frame static flow plus
  // the ~10 px/frame of walking people at 30 Hz once the pyramid divides it by 2^levels.
  int lk_window = 21;
  // Dynamic.LK.pyramidLevels: 3 extra levels (1/8 scale) follow flows up to ~8 * window/2 = 80 px per frame.
  int lk_levels = 3;
  // Dynamic.LK.maxIterations / epsilon: per-level Gauss-Newton stop, OpenCV defaults (0.01 px is far below
  // the corner localisation noise).
  int lk_max_iterations = 30;
  double lk_epsilon = 0.01;
  // Dynamic.LK.forwardBackwardThreshold: a static well-tracked corner returns within ~2 * 0.3 px (two LK runs at
  // ~0.3 px each); > 1 px means occlusion, a textureless window or a jump to another structure.
  double forward_backward_px = 1.0;
  void check() const;
};

// One correspondence in raw (distorted) pixel coordinates of both images.
struct PointTrack {
  cv::Point2f last;
  cv::Point2f current;
  int source_index = -1;  // index into the input point list (trackPoints) or the detected corners
};

// Pyramids of both frames, built once and shared by the forward and backward LK passes (and by several
// tracking calls on the same frame pair).
struct FramePairPyramids {
  std::vector<cv::Mat> last, current;
};
FramePairPyramids buildPyramids(const cv::Mat& last_gray, const cv::Mat& current_gray,
                                const CornerTrackingOptions& options);

// Tracks the given points of the last frame into the current one; returns only the tracks that converged,
// stay inside the image and pass the forward-backward check, in input order.
std::vector<PointTrack> trackPoints(const FramePairPyramids& pyramids, const std::vector<cv::Point2f>& points,
                                    const CornerTrackingOptions& options);

// Detects corners in the last frame (optionally only where mask != 0) and tracks them.
std::vector<PointTrack> trackCorners(const cv::Mat& last_gray, const cv::Mat& current_gray,
                                     const CornerTrackingOptions& options, const cv::Mat& mask = cv::Mat());

}  // namespace amos::dynamic
