#pragma once
// Pinhole camera with OpenCV's radial-tangential distortion (k1 k2 p1 p2 k3), as in ORB-SLAM2 settings files.
// Projection works on undistorted pixel coordinates; keypoints are undistorted once after extraction.
#include <opencv2/core.hpp>
#include <Eigen/Core>
#include <vector>

#include "amos/core/distortion.h"

namespace amos::core {

struct CameraIntrinsics {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  double k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0;
  int width = 640, height = 480;
  // Throws Error naming the offending field when the values cannot describe a camera.
  void check() const;
  bool hasDistortion() const { return k1 != 0 || k2 != 0 || p1 != 0 || p2 != 0 || k3 != 0; }
  RadialTangential lens() const { return {k1, k2, p1, p2, k3}; }
};

class PinholeCamera {
 public:
  PinholeCamera() = default;
  explicit PinholeCamera(const CameraIntrinsics& intrinsics);

  const CameraIntrinsics& intrinsics() const { return intr_; }
  double fx() const { return intr_.fx; }
  double fy() const { return intr_.fy; }
  double cx() const { return intr_.cx; }
  double cy() const { return intr_.cy; }
  int width() const { return intr_.width; }
  int height() const { return intr_.height; }

  // Pixel of a camera-frame point (z > 0 assumed by the caller).
  Eigen::Vector2d project(const Eigen::Vector3d& p_c) const {
    return {intr_.fx * p_c.x() / p_c.z() + intr_.cx, intr_.fy * p_c.y() / p_c.z() + intr_.cy};
  }
  // Camera-frame point at depth z (metres) behind undistorted pixel (u, v).
  Eigen::Vector3d backProject(double u, double v, double z) const {
    return {(u - intr_.cx) * z / intr_.fx, (v - intr_.cy) * z / intr_.fy, z};
  }
  bool inImage(double u, double v, double border = 0) const {
    return u >= border && v >= border && u < intr_.width - border && v < intr_.height - border;
  }

  cv::Mat K() const;           // 3x3 CV_64F
  cv::Mat distortion() const;  // 1x5 CV_64F
  Eigen::Matrix3d eigenK() const;

  // Undistorts pixel coordinates (returns them unchanged when there is no distortion).
  std::vector<cv::Point2f> undistort(const std::vector<cv::Point2f>& pixels) const;
  // The inverse: raw (distorted) pixels of undistorted ones (unchanged when there is no distortion).
  std::vector<cv::Point2f> distort(const std::vector<cv::Point2f>& undistorted) const;
  // Bounds of the undistorted image (min_u, max_u, min_v, max_v): where undistorted keypoints can fall.
  cv::Rect2d undistortedBounds() const;

 private:
  CameraIntrinsics intr_;
  cv::Mat K_, dist_;
};

}  // namespace amos::core
