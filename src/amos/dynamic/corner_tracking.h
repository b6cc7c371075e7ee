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
  // Dynamic.Corners.minDistance: 10 px (full resolution) spreads the corners over the image.
  double min_distance_px = 10.0;
  // Dynamic.Corners.detectionScale: corners are detected on an image downscaled by this factor (a quarter of the
  // pixels at 0.5) and tracked at full resolution. LK needs a well-textured window, not a precisely localised
  // corner, and the forward-backward check rejects the windows that track badly.
  double detection_scale = 0.5;
  // Dynamic.LK.window: 15x15 px: with 3 pyramid levels it follows flows up to 7 * 2^3 = 56 px per frame, above
  // a person walking 1.5 m/s at 1.5 m (~18 px at 30 Hz, f ~ 540 px) or a camera turning 1 rad/s (~18 px), at
  // half the cost of OpenCV's default 21x21 window. 11 (5 * 2^3 = 40 px, still twice those flows) halves LK's cost
  // again, which grows with the window's area, at the same accuracy on real data (docs/experiments/
  // front-end-defaults.md): set in the configs; the default stays 15 for the synthetic front-end tests built on it.
  int lk_window = 15;
  // Dynamic.LK.pyramidLevels: 3 extra levels (1/8 scale), see the window.
  int lk_levels = 3;
  // Dynamic.LK.maxIterations / epsilon: per-level Gauss-Newton stop. A step below 0.03 px is a tenth of the
  // corner localisation noise (~0.3 px), so iterating on to OpenCV's 0.01 px (30 iterations) buys nothing that a
  // later test can see, at a lower cost (docs/experiments/front-end-defaults.md).
  int lk_max_iterations = 10;
  double lk_epsilon = 0.03;
  // Dynamic.LK.forwardBackwardThreshold: a static well-tracked corner returns within ~2 * 0.3 px (two LK runs at
  // ~0.3 px each); > 1 px means occlusion, a textureless window or a jump to another structure.
  double forward_backward_px = 1.0;
  // Whether trackPoints runs the backward pass at all (it doubles the LK cost). Off, every forward track that
  // converged inside the image is kept: for callers that reject outliers themselves (the reference-keyframe pose
  // model's EPnP RANSAC, which rejects the tracks that went astray as it rejects wrong matches, at half the LK cost).
  // Dynamic.LK.forwardBackward (for the corner tracks).
  bool forward_backward_check = true;
  void check() const;
};

// One correspondence in raw (distorted) pixel coordinates of both images.
struct PointTrack {
  cv::Point2f last;
  cv::Point2f current;
  int source_index = -1;  // index into the input point list (trackPoints) or the detected corners
};

// LK pyramid of one image (levels with their derivatives, as cv::buildOpticalFlowPyramid makes them). A frame's
// pyramid depends on nothing but the frame, so it is built once and serves every tracking call the frame takes
// part in: as `current` for last->current corners and keyframe->current points, as `last` on the next frame, and
// as the keyframe side while the frame is a reference keyframe.
using ImagePyramid = std::vector<cv::Mat>;
ImagePyramid buildPyramid(const cv::Mat& gray, const CornerTrackingOptions& options);

// Pyramids of both frames, shared by the forward and backward LK passes (and by several tracking calls on the same
// frame pair).
struct FramePairPyramids {
  ImagePyramid last, current;
};
FramePairPyramids buildPyramids(const cv::Mat& last_gray, const cv::Mat& current_gray,
                                const CornerTrackingOptions& options);

// Tracks the given points of the last frame into the current one; returns only the tracks that converged,
// stay inside the image and pass the forward-backward check, in input order.
std::vector<PointTrack> trackPoints(const FramePairPyramids& pyramids, const std::vector<cv::Point2f>& points,
                                    const CornerTrackingOptions& options);

// Shi-Tomasi corners of one frame (optionally only where mask != 0), found at options.detection_scale and returned
// in full-resolution pixels, strongest first. They depend on nothing but that frame, so a frame's corners can be
// found ahead (e.g. while the frame before it is tracked) and tracked with trackPoints once the next frame exists.
std::vector<cv::Point2f> detectCorners(const cv::Mat& gray, const CornerTrackingOptions& options,
                                       const cv::Mat& mask = cv::Mat());

// Detects corners in the last frame (optionally only where mask != 0) and tracks them: detectCorners + trackPoints.
std::vector<PointTrack> trackCorners(const cv::Mat& last_gray, const cv::Mat& current_gray,
                                     const CornerTrackingOptions& options, const cv::Mat& mask = cv::Mat());
// The same on pyramids built beforehand (pyramids.last must be last_gray's).
std::vector<PointTrack> trackCorners(const cv::Mat& last_gray, const FramePairPyramids& pyramids,
                                     const CornerTrackingOptions& options, const cv::Mat& mask = cv::Mat());

}  // namespace amos::dynamic
