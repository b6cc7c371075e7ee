#pragma once
// Camera motions after the TUM fr3 set (Sturm et al. 2012): a hand-held camera that is almost static, moves
// along its x/y/z axes, rotates about roll/pitch/yaw, or moves on a half sphere of 1 m diameter while looking at
// a desk; plus a room-scale loop for SLAM accuracy. Every path is a smooth analytic function of time (pose at
// any t, no integration), seeded only by the sequence seed: a dynamic preset and its static counterpart with
// the same motion and seed fly exactly the same path.
#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "amos/core/pose.h"

namespace amos::synth {

enum class CameraMotion { kStatic, kXyz, kRpy, kHalfsphere, kLoop };

std::string toString(CameraMotion motion);
// "static" | "xyz" | "rpy" | "halfsphere" | "loop"; throws core::Error otherwise.
CameraMotion cameraMotionFromString(const std::string& name);

// Where the paths are anchored in the room (world: z up, metres).
struct CameraStage {
  Eigen::Vector3d eye{-0.4, 0.0, 1.35};    // rest position of the desk-facing motions
  Eigen::Vector3d target{1.9, 0.0, 0.85};  // the point they look at (the desk)
  Eigen::Vector2d loop_centre{0.0, 0.0};   // room-scale loop: an ellipse on the floor plan
  Eigen::Vector2d loop_radii{1.0, 0.8};
  double loop_height = 1.4;
  double loop_period_s = 20.0;  // one lap; the loop closes after this time
};

// Rotation R_wc of a camera looking along `forward` with the world's z axis up in the image (x right, y down).
Eigen::Matrix3d lookAtRotation(const Eigen::Vector3d& forward);

class CameraPath {
 public:
  CameraPath(CameraMotion motion, const CameraStage& stage, std::uint32_t seed);

  // Camera-to-world pose at time t seconds after the first frame.
  core::SE3 poseWc(double t) const;
  CameraMotion motion() const { return motion_; }

 private:
  struct Wave {
    double amplitude = 0, frequency_hz = 0, phase = 0;
    double at(double t) const;
  };
  // Hand-held shake: three waves per translation / rotation axis.
  Eigen::Vector3d shakeTranslation(double t) const;
  Eigen::Vector3d shakeRotation(double t) const;

  CameraMotion motion_;
  CameraStage stage_;
  Wave shake_[6][3];
  Wave main_[3];
  double phase0_ = 0;
};

}  // namespace amos::synth
