#include "amos/synth/camera_path.h"

#include <cmath>

#include "amos/core/error.h"
#include "amos/synth/random.h"

namespace amos::synth {

namespace {
constexpr double kDeg = M_PI / 180.0;

Eigen::Matrix3d rotX(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix(); }
Eigen::Matrix3d rotY(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
Eigen::Matrix3d rotZ(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

// Rotation of the camera by yaw (about its y, pointing down), pitch (about x, right) and roll (about z, the
// optical axis), applied in the camera frame.
Eigen::Matrix3d cameraYawPitchRoll(double yaw, double pitch, double roll) {
  return rotY(yaw) * rotX(pitch) * rotZ(roll);
}
}  // namespace

std::string toString(CameraMotion motion) {
  switch (motion) {
    case CameraMotion::kStatic:
      return "static";
    case CameraMotion::kXyz:
      return "xyz";
    case CameraMotion::kRpy:
      return "rpy";
    case CameraMotion::kHalfsphere:
      return "halfsphere";
    case CameraMotion::kLoop:
      return "loop";
  }
  return "?";
}

CameraMotion cameraMotionFromString(const std::string& name) {
  for (CameraMotion m :
       {CameraMotion::kStatic, CameraMotion::kXyz, CameraMotion::kRpy, CameraMotion::kHalfsphere, CameraMotion::kLoop})
    if (toString(m) == name) return m;
  throw core::Error("unknown camera motion '" + name + "' (static, xyz, rpy, halfsphere, loop)");
}

Eigen::Matrix3d lookAtRotation(const Eigen::Vector3d& forward) {
  const Eigen::Vector3d z = forward.normalized();
  Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ());
  if (x.norm() < 1e-9) x = Eigen::Vector3d::UnitY();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = y;
  R.col(2) = z;
  return R;
}

double CameraPath::Wave::at(double t) const { return amplitude * std::sin(2 * M_PI * frequency_hz * t + phase); }

CameraPath::CameraPath(CameraMotion motion, const CameraStage& stage, std::uint32_t seed)
    : motion_(motion), stage_(stage) {
  Random rng(deriveSeed(seed, Stream::kCameraPath));
  // Shake: a few mm and a few tenths of a degree, 0.3-1.6 Hz (TUM fr3/walking_static moves 1.2 cm/s, 1.4 deg/s).
  const bool still = motion == CameraMotion::kStatic;
  for (int axis = 0; axis < 6; ++axis)
    for (int k = 0; k < 3; ++k) {
      const double amp = axis < 3 ? (still ? 0.0030 : 0.0020) : (still ? 0.25 : 0.15) * kDeg;
      shake_[axis][k] = {amp / (k + 1), rng.uniform(0.3, 0.7) * (k + 1), rng.uniform(0, 2 * M_PI)};
    }
  for (Wave& w : main_) w.phase = rng.uniform(0, 2 * M_PI);
  phase0_ = rng.uniform(0, 2 * M_PI);
  switch (motion) {
    case CameraMotion::kXyz:  // along the camera's x, y, z axes (metres)
      main_[0].amplitude = 0.35, main_[0].frequency_hz = 0.10;
      main_[1].amplitude = 0.15, main_[1].frequency_hz = 0.13;
      main_[2].amplitude = 0.25, main_[2].frequency_hz = 0.08;
      break;
    case CameraMotion::kRpy:  // yaw, pitch, roll (radians)
      main_[0].amplitude = 30 * kDeg, main_[0].frequency_hz = 0.15;
      main_[1].amplitude = 15 * kDeg, main_[1].frequency_hz = 0.20;
      main_[2].amplitude = 20 * kDeg, main_[2].frequency_hz = 0.12;
      break;
    case CameraMotion::kHalfsphere:  // azimuth, elevation (radians) on a sphere of 0.5 m radius
      main_[0].amplitude = 70 * kDeg, main_[0].frequency_hz = 1.0 / 12;
      main_[1].amplitude = 25 * kDeg, main_[1].frequency_hz = 1.0 / 17;
      break;
    default:
      break;
  }
}

Eigen::Vector3d CameraPath::shakeTranslation(double t) const {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a)
    for (const Wave& w : shake_[a]) v[a] += w.at(t);
  return v;
}

Eigen::Vector3d CameraPath::shakeRotation(double t) const {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a)
    for (const Wave& w : shake_[3 + a]) v[a] += w.at(t);
  return v;
}

core::SE3 CameraPath::poseWc(double t) const {
  Eigen::Matrix3d R = lookAtRotation(stage_.target - stage_.eye);
  Eigen::Vector3d p = stage_.eye;
  switch (motion_) {
    case CameraMotion::kStatic:
      break;
    case CameraMotion::kXyz:
      p += R * Eigen::Vector3d(main_[0].at(t), main_[1].at(t), main_[2].at(t));
      break;
    case CameraMotion::kRpy:
      R = R * cameraYawPitchRoll(main_[0].at(t), main_[1].at(t), main_[2].at(t));
      break;
    case CameraMotion::kHalfsphere: {
      // Sphere of 0.5 m radius around a point 0.5 m behind the rest position, bulging towards the desk.
      const double az = main_[0].at(t), el = 25 * kDeg + main_[1].at(t);
      const Eigen::Vector3d f = R.col(2), right = R.col(0), up = Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d fh = (f - f.dot(up) * up).normalized();
      const Eigen::Vector3d centre = stage_.eye - 0.5 * fh;
      p = centre + 0.5 * (std::cos(el) * std::cos(az) * fh + std::cos(el) * std::sin(az) * right + std::sin(el) * up);
      // Look at the desk, turned further in the direction of travel (about TUM's 18 deg/s on average).
      R = lookAtRotation(stage_.target - p) * cameraYawPitchRoll(0.9 * az, 0.6 * (el - 25 * kDeg), 0);
      break;
    }
    case CameraMotion::kLoop: {
      const double theta = phase0_ + 2 * M_PI * t / stage_.loop_period_s;
      const double a = stage_.loop_radii.x(), b = stage_.loop_radii.y();
      p = Eigen::Vector3d(stage_.loop_centre.x() + a * std::cos(theta), stage_.loop_centre.y() + b * std::sin(theta),
                          stage_.loop_height + 0.08 * std::sin(2 * theta + phase0_));
      // Walking anticlockwise, looking 55 degrees outwards from the direction of travel at the walls and
      // furniture (1-4 m away), slightly down, with a slow glance left and right.
      const double heading =
          std::atan2(b * std::cos(theta), -a * std::sin(theta)) - 55 * kDeg + 8 * kDeg * std::sin(3 * theta + phase0_);
      const Eigen::Vector3d forward(std::cos(heading), std::sin(heading), 0);
      R = lookAtRotation(forward) * cameraYawPitchRoll(0, -(10 + 5 * std::sin(2 * theta)) * kDeg, 0);
      break;
    }
  }
  R = R * cameraYawPitchRoll(shakeRotation(t).y(), shakeRotation(t).x(), shakeRotation(t).z());
  p += shakeTranslation(t);
  core::SE3 T = core::SE3::Identity();
  T.linear() = R;
  T.translation() = p;
  return T;
}

}  // namespace amos::synth
