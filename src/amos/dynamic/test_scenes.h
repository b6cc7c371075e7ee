#pragma once
// Cameras and frames the dynamic module's tests build their scenes on (header-only, included by *_test.cc only).
#include <opencv2/core.hpp>

#include "amos/core/camera.h"
#include "amos/dynamic/dynamic_front_end.h"
#include "amos/testing/test_camera.h"

namespace amos::dynamic {

// The shared test cameras (amos/testing/test_camera.h): TUM fr3's colour camera, 640 x 480, and the hand-written
// scenes' 120 x 100 camera with f = 100 px.
using testing::smallTestCamera;
using testing::testCamera;

// A frame pair looking at a wall depth_m away, with the same (identity) pose in both frames; gray is black.
inline DynamicFrameInput wallFramePair(cv::Size size, float depth_m) {
  DynamicFrameInput in;
  in.gray = cv::Mat(size, CV_8U, cv::Scalar(0));
  in.depth = cv::Mat(size, CV_32F, cv::Scalar(depth_m));
  in.last_depth = in.depth.clone();
  return in;
}

}  // namespace amos::dynamic
