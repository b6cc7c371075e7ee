#pragma once
// For tests only: GoogleTest matchers for poses (link GTest::gmock for EXPECT_THAT).
//   EXPECT_THAT(estimate.T_cw, testing::PoseNear(truth_T_cw, 0.01, 0.5 * M_PI / 180));
// A failure names both errors, e.g. "translation error 0.0231 m (max 0.01), rotation error 0.12 deg (max 0.5)",
// and prints both poses as translation + rotation vector instead of the bytes of an Eigen::Isometry3d.
#include <gmock/gmock.h>

#include <cmath>
#include <ostream>

#include "amos/core/pose.h"

namespace amos::testing {

// How far apart two poses are: |t| and the angle of the relative transform actual * expected^-1. For T_cw poses
// that is the camera's rotation angle and the translation error seen from the camera.
struct PoseError {
  double translation_m = 0;
  double rotation_rad = 0;
};

inline PoseError poseError(const core::SE3& actual, const core::SE3& expected) {
  const core::SE3 delta = actual * expected.inverse();
  return {core::translationNorm(delta), core::rotationAngle(delta)};
}

// "t = (x, y, z) m, r = (rx, ry, rz) rad" (r: rotation vector).
inline void printPose(const core::SE3& T, std::ostream* os) {
  const Eigen::Vector3d t = T.translation();
  const Eigen::Vector3d r = core::logSO3(T.linear());
  *os << "t = (" << t.x() << ", " << t.y() << ", " << t.z() << ") m, r = (" << r.x() << ", " << r.y() << ", "
      << r.z() << ") rad";
}

class PoseNearMatcher {
 public:
  using is_gtest_matcher = void;

  PoseNearMatcher(const core::SE3& expected, double max_translation_m, double max_rotation_rad)
      : expected_(expected), max_translation_m_(max_translation_m), max_rotation_rad_(max_rotation_rad) {}

  bool MatchAndExplain(const core::SE3& actual, std::ostream* os) const {
    const PoseError e = poseError(actual, expected_);
    const bool ok = e.translation_m <= max_translation_m_ && e.rotation_rad <= max_rotation_rad_;
    if (os != nullptr) {
      *os << "translation error " << e.translation_m << " m (max " << max_translation_m_ << "), rotation error "
          << e.rotation_rad * 180 / M_PI << " deg (max " << max_rotation_rad_ * 180 / M_PI << ")";
    }
    return ok;
  }
  void DescribeTo(std::ostream* os) const {
    *os << "is within " << max_translation_m_ << " m and " << max_rotation_rad_ * 180 / M_PI << " deg of ";
    printPose(expected_, os);
  }
  void DescribeNegationTo(std::ostream* os) const {
    *os << "is farther than " << max_translation_m_ << " m or " << max_rotation_rad_ * 180 / M_PI << " deg from ";
    printPose(expected_, os);
  }

 private:
  core::SE3 expected_;
  double max_translation_m_, max_rotation_rad_;
};

// Matches a core::SE3 whose translation and rotation differ from `expected` by at most the given bounds.
inline ::testing::Matcher<const core::SE3&> PoseNear(const core::SE3& expected, double max_translation_m,
                                                     double max_rotation_rad) {
  return PoseNearMatcher(expected, max_translation_m, max_rotation_rad);
}

}  // namespace amos::testing

// GoogleTest prints a value through PrintTo found by argument-dependent lookup, i.e. in the namespace of
// Eigen::Isometry3d (core::SE3); without it a failing pose is printed as its raw bytes.
namespace Eigen {
inline void PrintTo(const Isometry3d& T, std::ostream* os) { amos::testing::printPose(T, os); }
}  // namespace Eigen
