#pragma once
// Cameras and frames the dynamic module's tests build their scenes on (header-only, included by *_test.cc only).
#include <opencv2/core.hpp>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/front_end_types.h"
#include "amos/testing/test_camera.h"

namespace amos::dynamic {

// The shared test cameras (amos/testing/test_camera.h): TUM fr3's colour camera, 640 x 480, and the hand-written
// scenes' 120 x 100 camera with f = 100 px.
using testing::smallTestCamera;
using testing::testCamera;

// A frame pair looking at a wall depth_m away, with the same (identity) pose in both frames; gray is black.
inline FrontEndInput wallFramePair(cv::Size size, float depth_m) {
  FrontEndInput in;
  in.gray = cv::Mat(size, CV_8U, cv::Scalar(0));
  in.depth = cv::Mat(size, CV_32F, cv::Scalar(depth_m));
  in.last_depth = in.depth.clone();
  return in;
}

// T_cw of a camera at `centre` (world frame) looking along +z without rotation.
inline core::SE3 poseAt(const Eigen::Vector3d& centre) {
  core::SE3 T_wc = core::SE3::Identity();
  T_wc.translation() = centre;
  return T_wc.inverse();
}

// Superpixels (or clusters) as kTestBlock x kTestBlock pixel blocks over the camera's image, numbered row by row;
// count receives their number.
inline constexpr int kTestBlock = 40;
inline cv::Mat blockLabels(const core::PinholeCamera& camera, int& count) {
  const int cols = (camera.width() + kTestBlock - 1) / kTestBlock;
  const int rows = (camera.height() + kTestBlock - 1) / kTestBlock;
  count = cols * rows;
  cv::Mat labels(camera.height(), camera.width(), CV_32S);
  for (int v = 0; v < labels.rows; ++v)
    for (int u = 0; u < labels.cols; ++u) labels.at<int>(v, u) = (v / kTestBlock) * cols + u / kTestBlock;
  return labels;
}
// The block of pixel (u, v) in blockLabels.
inline int blockAt(const core::PinholeCamera& camera, int u, int v) {
  return (v / kTestBlock) * ((camera.width() + kTestBlock - 1) / kTestBlock) + u / kTestBlock;
}

}  // namespace amos::dynamic
