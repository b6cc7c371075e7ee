#pragma once
// What the long-baseline tracks found (evidence/baseline_tracks.h): the front end hands it on to the rigid movers,
// the cluster decision and the result (FrontEndResult::baseline_points).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace amos::dynamic {

struct BaselinePoint {
  cv::Point2f current;    // raw pixel in the current frame
  cv::Point2f found;      // raw pixel where LK found it in the baseline frame
  double residual_px = 0;  // |found - prediction - common shift| (undistorted pixels)
  bool moving = false;
};

struct BaselineMotion {
  std::vector<BaselinePoint> points;  // those with a trusted depth that LK followed both ways
  bool ok = false;                    // enough points (Dynamic.Reprojection.refitMinPoints) to judge any
  Eigen::Vector2d shift_px = Eigen::Vector2d::Zero();  // the median residual, removed from every point
  double sigma_px = 0;                // the points' noise scale around it
  double bar_px = 0;                  // max(min_motion_px, sigmas * sigma_px)
  int moving_points = 0;
};

}  // namespace amos::dynamic
