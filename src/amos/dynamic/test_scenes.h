#pragma once
// Cameras and frames the dynamic module's tests build their scenes on (header-only, included by *_test.cc only).
#include <opencv2/core.hpp>

#include "amos/core/camera.h"
#include "amos/dynamic/dynamic_front_end.h"

namespace amos::dynamic {

// TUM fr3's colour camera without distortion, 640 x 480.
inline core::PinholeCamera testCamera() {
  core::CameraIntrinsics intr;
  intr.fx = 535.4, intr.fy = 539.2, intr.cx = 320.1, intr.cy = 247.6;
  return core::PinholeCamera(intr);
}

// A 120 x 100 camera with f = 100 px and the principal point in the middle: scenes small enough to write by hand.
inline core::PinholeCamera smallTestCamera() {
  core::CameraIntrinsics intr;
  intr.fx = intr.fy = 100, intr.cx = 60, intr.cy = 50, intr.width = 120, intr.height = 100;
  return core::PinholeCamera(intr);
}

// A frame pair looking at a wall depth_m away, with the same (identity) pose in both frames; gray is black.
inline DynamicFrameInput wallFramePair(cv::Size size, float depth_m) {
  DynamicFrameInput in;
  in.gray = cv::Mat(size, CV_8U, cv::Scalar(0));
  in.depth = cv::Mat(size, CV_32F, cv::Scalar(depth_m));
  in.last_depth = in.depth.clone();
  return in;
}

}  // namespace amos::dynamic
