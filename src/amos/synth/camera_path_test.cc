#include "amos/synth/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "amos/core/error.h"

namespace amos::synth {
namespace {

struct Speeds {
  double mean_mps = 0, max_mps = 0, mean_dps = 0, max_dps = 0;
};

Speeds measure(const CameraPath& path, double seconds, double fps = 30) {
  Speeds s;
  const int n = static_cast<int>(seconds * fps);
  for (int k = 0; k < n; ++k) {
    const core::SE3 a = path.poseWc(k / fps), b = path.poseWc((k + 1) / fps);
    const double v = (b.translation() - a.translation()).norm() * fps;
    const double w = core::rotationAngle(a.inverse() * b) * fps * 180 / M_PI;
    s.mean_mps += v / n;
    s.mean_dps += w / n;
    s.max_mps = std::max(s.max_mps, v);
    s.max_dps = std::max(s.max_dps, w);
  }
  return s;
}

TEST(CameraPath, SpeedsAreLikeTumFr3AndWithinTheLimits) {
  // TUM fr3 (benchmark web page): walking_static 0.012 m/s 1.4 deg/s, walking_xyz 0.21 m/s 5.5 deg/s,
  // walking_rpy 0.09 m/s 24 deg/s, walking_halfsphere 0.22 m/s 18 deg/s; the issue caps 0.4 m/s and 40 deg/s.
  const CameraStage stage;
  struct Expect {
    CameraMotion motion;
    double mps_lo, mps_hi, dps_lo, dps_hi;
  };
  for (const Expect& e :
       {Expect{CameraMotion::kStatic, 0.0, 0.03, 0.0, 3.0}, Expect{CameraMotion::kXyz, 0.1, 0.3, 0.0, 5.0},
        Expect{CameraMotion::kRpy, 0.0, 0.05, 10.0, 35.0}, Expect{CameraMotion::kHalfsphere, 0.1, 0.35, 10.0, 30.0},
        Expect{CameraMotion::kLoop, 0.2, 0.4, 10.0, 30.0}}) {
    for (std::uint32_t seed : {1u, 2u, 3u}) {
      const Speeds s = measure(CameraPath(e.motion, stage, seed), 60);
      if (seed == 1)
        std::cout << toString(e.motion) << ": mean " << s.mean_mps << " m/s (max " << s.max_mps << "), mean "
                  << s.mean_dps << " deg/s (max " << s.max_dps << ")\n";
      EXPECT_GE(s.mean_mps, e.mps_lo) << toString(e.motion);
      EXPECT_LE(s.mean_mps, e.mps_hi) << toString(e.motion);
      EXPECT_GE(s.mean_dps, e.dps_lo) << toString(e.motion);
      EXPECT_LE(s.mean_dps, e.dps_hi) << toString(e.motion);
      EXPECT_LE(s.max_mps, 0.42) << toString(e.motion);
      EXPECT_LE(s.max_dps, 40.0) << toString(e.motion);
    }
  }
}

TEST(CameraPath, LoopClosesAndStaysClearOfTheFurniture) {
  const CameraStage stage;
  const CameraPath path(CameraMotion::kLoop, stage, 5);
  const core::SE3 start = path.poseWc(0), lap = path.poseWc(stage.loop_period_s);
  EXPECT_LT(core::translationNorm(start.inverse() * lap), 0.01);  // only the hand shake differs
  EXPECT_LT(core::rotationAngle(start.inverse() * lap), 0.5 * M_PI / 180);
  EXPECT_GT(core::translationNorm(start.inverse() * path.poseWc(stage.loop_period_s / 2)), 1.5);
  for (double t = 0; t < stage.loop_period_s; t += 0.1) {
    const Eigen::Vector3d p = path.poseWc(t).translation();
    EXPECT_LE(std::abs(p.x()), 1.1);
    EXPECT_LE(std::abs(p.y()), 0.9);
    EXPECT_NEAR(p.z(), 1.4, 0.1);
  }
}

TEST(CameraPath, LookAtKeepsTheWorldUpUpInTheImage) {
  const Eigen::Matrix3d R = lookAtRotation(Eigen::Vector3d(1, 0, 0));
  EXPECT_TRUE(R.isUnitary(1e-12));
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
  EXPECT_TRUE(R.col(2).isApprox(Eigen::Vector3d(1, 0, 0)));   // optical axis forward
  EXPECT_TRUE(R.col(1).isApprox(Eigen::Vector3d(0, 0, -1)));  // image y points down
  EXPECT_TRUE(R.col(0).isApprox(Eigen::Vector3d(0, -1, 0)));  // image x to the right
}

TEST(CameraPath, SeedFixesThePath) {
  const CameraStage stage;
  for (CameraMotion m : {CameraMotion::kStatic, CameraMotion::kXyz, CameraMotion::kRpy, CameraMotion::kHalfsphere,
                         CameraMotion::kLoop}) {
    EXPECT_TRUE(CameraPath(m, stage, 9).poseWc(3.3).isApprox(CameraPath(m, stage, 9).poseWc(3.3), 0));
    EXPECT_FALSE(CameraPath(m, stage, 9).poseWc(3.3).isApprox(CameraPath(m, stage, 10).poseWc(3.3), 1e-9));
    EXPECT_EQ(cameraMotionFromString(toString(m)), m);
  }
  EXPECT_THROW(cameraMotionFromString("spiral"), core::Error);
}

}  // namespace
}  // namespace amos::synth
