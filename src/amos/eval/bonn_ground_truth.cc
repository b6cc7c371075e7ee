#include "amos/eval/bonn_ground_truth.h"

#include <Eigen/SVD>

namespace amos::eval {
namespace {

core::SE3 rosToOptical() {
  core::SE3 T = core::SE3::Identity();
  T.linear() << -1, 0, 0,  //
      0, 0, 1,             //
      0, 1, 0;
  return T;
}

// T_cam = left * T_marker * right.
struct Conversion {
  core::SE3 left, right;
};

Conversion conversion() {
  const core::SE3 T_ros = rosToOptical();
  return {T_ros.inverse(), T_ros * bonnMarkerToCameraCalibration()};  // T_ROS is a rotation: inverse = transpose
}

}  // namespace

core::SE3 bonnMarkerToCameraCalibration() {
  Eigen::Matrix3d M;
  M << 1.0157, 0.1828, -0.2389,  //
      0.0009, -0.8431, -0.6413,  //
      -0.3009, 0.6147, -0.8085;
  // Closest rotation in the Frobenius norm: U V^T, with the sign fix that keeps det = +1.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d S(1, 1, 1);
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) S.z() = -1;
  core::SE3 T = core::SE3::Identity();
  T.linear() = svd.matrixU() * S.asDiagonal() * svd.matrixV().transpose();
  T.translation() = Eigen::Vector3d(0.0113, -0.0098, 0.0111);
  return T;
}

core::SE3 bonnMarkerToCamera(const core::SE3& T_marker) {
  const Conversion c = conversion();
  return c.left * T_marker * c.right;
}

std::vector<io::StampedPose> bonnMarkerToCamera(const std::vector<io::StampedPose>& marker_poses) {
  const Conversion c = conversion();
  std::vector<io::StampedPose> camera_poses;
  camera_poses.reserve(marker_poses.size());
  for (const io::StampedPose& pose : marker_poses)
    camera_poses.push_back({pose.timestamp, c.left * pose.T_wc * c.right});
  return camera_poses;
}

}  // namespace amos::eval
