#pragma once
// The Bonn RGB-D Dynamic Dataset's groundtruth.txt holds the pose of the motion-capture marker body, not of the
// camera. Its readme gives the conversion T_cam = T_ROS^T * T_gt * T_ROS * T_m with
//   T_ROS = [[-1,0,0,0],[0,0,1,0],[0,1,0,0],[0,0,0,1]] (ROS body axes to optical axes) and
//   T_m   = [[1.0157,0.1828,-0.2389,0.0113],[0.0009,-0.8431,-0.6413,-0.0098],[-0.3009,0.6147,-0.8085,0.0111],[0,0,0,1]]
//   (marker-to-camera calibration). The rotation block of T_m carries a uniform scale of about 1.059; it is
//   replaced by the closest rotation (SVD) so that the converted poses are rigid; its translation is kept.
// ATE after rigid alignment barely changes with the conversion, RPE does: report Bonn RPE against the converted
// ground truth (see /work/shared/data/README.md).
#include <vector>

#include "amos/core/pose.h"
#include "amos/io/trajectory.h"

namespace amos::eval {

// T_m with its rotation block orthonormalised.
core::SE3 bonnMarkerToCameraCalibration();

// Camera pose (camera-to-world) from one marker pose of groundtruth.txt.
core::SE3 bonnMarkerToCamera(const core::SE3& T_marker);

// The whole ground-truth trajectory converted; stamps unchanged.
std::vector<io::StampedPose> bonnMarkerToCamera(const std::vector<io::StampedPose>& marker_poses);

}  // namespace amos::eval
