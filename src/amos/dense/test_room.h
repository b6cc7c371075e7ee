#pragma once
// For the tests: a closed room (x, y in [-2, 2] m, z up in [0, 2.5] m, floor at z = 0) with solid boxes in it,
// rendered exactly (depth along the optical axis, a colour per surface, a mask of the boxes marked as movers) by
// ray casting from a small pinhole camera. Known answers: every static surface is a plane of the room or a face
// of a static box.
#include <opencv2/core.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"

namespace amos::dense::testing {

struct Box {
  Eigen::Vector3d low, high;
  bool mover = false;  // its pixels are marked in the dynamic mask
};

inline core::CameraIntrinsics roomCamera() {
  core::CameraIntrinsics k;
  k.width = 160;
  k.height = 120;
  k.fx = k.fy = 110;
  k.cx = 79.5;
  k.cy = 59.5;
  return k;
}

// A camera at `centre` looking along yaw (about z, from +x) and pitch (negative: down): x right, y down, z forward.
inline core::SE3 cameraPose(const Eigen::Vector3d& centre, double yaw, double pitch) {
  const Eigen::Vector3d forward(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch));
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d down = forward.cross(right);
  core::SE3 T_wc = core::SE3::Identity();
  T_wc.linear().col(0) = right;
  T_wc.linear().col(1) = down;
  T_wc.linear().col(2) = forward;
  T_wc.translation() = centre;
  return T_wc;
}

struct RoomFrame {
  cv::Mat depth, bgr, mask;  // CV_32F m, CV_8UC3, CV_8U (255 = mover)
};

// Distance along the ray to where it leaves the room's inside.
inline double roomExit(const Eigen::Vector3d& c, const Eigen::Vector3d& d, int& axis) {
  const Eigen::Vector3d low(-2, -2, 0), high(2, 2, 2.5);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) continue;
    const double t = ((d[i] > 0 ? high[i] : low[i]) - c[i]) / d[i];
    if (t < best) {
      best = t;
      axis = i;
    }
  }
  return best;
}

// Distance along the ray to where it enters `box` (infinity when it misses).
inline double boxEntry(const Box& box, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  double near = 0, far = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (c[i] < box.low[i] || c[i] > box.high[i]) return std::numeric_limits<double>::infinity();
      continue;
    }
    double t0 = (box.low[i] - c[i]) / d[i], t1 = (box.high[i] - c[i]) / d[i];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
  }
  return near <= far && near > 0 ? near : std::numeric_limits<double>::infinity();
}

inline RoomFrame renderRoom(const core::CameraIntrinsics& k, const core::SE3& T_wc, const std::vector<Box>& boxes) {
  RoomFrame f{cv::Mat::zeros(k.height, k.width, CV_32F), cv::Mat::zeros(k.height, k.width, CV_8UC3),
              cv::Mat::zeros(k.height, k.width, CV_8U)};
  const Eigen::Vector3d c = T_wc.translation();
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      const Eigen::Vector3d ray_c((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);  // z = 1: t is the depth
      const Eigen::Vector3d d = T_wc.linear() * ray_c;
      int axis = 0;
      double t = roomExit(c, d, axis);
      cv::Vec3b colour(60 + 60 * axis, 120, 200 - 60 * axis);
      bool mover = false;
      for (const Box& box : boxes) {
        const double tb = boxEntry(box, c, d);
        if (tb < t) {
          t = tb;
          colour = box.mover ? cv::Vec3b(0, 0, 255) : cv::Vec3b(0, 200, 0);
          mover = box.mover;
        }
      }
      f.depth.at<float>(v, u) = static_cast<float>(t);
      f.bgr.at<cv::Vec3b>(v, u) = colour;
      f.mask.at<unsigned char>(v, u) = mover ? 255 : 0;
    }
  }
  return f;
}

// Distance of p to the nearest surface of the room and of the static boxes (to a box's faces: p outside or on it).
inline double distanceToStatic(const Eigen::Vector3d& p, const std::vector<Box>& boxes) {
  double d = std::min({std::abs(p.x() + 2), std::abs(p.x() - 2), std::abs(p.y() + 2), std::abs(p.y() - 2),
                       std::abs(p.z()), std::abs(p.z() - 2.5)});
  for (const Box& box : boxes) {
    if (box.mover) continue;
    const Eigen::Vector3d outside = (box.low - p).cwiseMax(p - box.high).cwiseMax(0.0);
    const Eigen::Vector3d inside = (p - box.low).cwiseMin(box.high - p);
    d = std::min(d, outside.norm() > 0 ? outside.norm() : inside.minCoeff());
  }
  return d;
}

}  // namespace amos::dense::testing
