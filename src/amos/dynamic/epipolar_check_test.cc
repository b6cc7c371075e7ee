#include "amos/dynamic/epipolar_check.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <random>

#include "amos/core/error.h"
#include "amos/testing/test_camera.h"

namespace amos::dynamic {
namespace {

Eigen::Matrix3d testK() { return testing::testCamera().eigenK(); }

Eigen::Vector2d project(const Eigen::Matrix3d& K, const Eigen::Vector3d& p) { return (K * p).hnormalized(); }

core::SE3 testMotion() {
  core::Vector6d xi;
  xi << 0.05, -0.01, 0.02, 0.01, 0.03, -0.02;  // last camera -> current camera
  return core::expSE3(xi);
}

TEST(EpipolarDistance, IsZeroForARigidPointAndMeasuresAnOffsetAcrossTheLine) {
  const Eigen::Matrix3d K = testK();
  const core::SE3 T_cl = testMotion();
  const Eigen::Matrix3d F = fundamentalFromPose(K, T_cl);
  const Eigen::Vector3d p_l(0.3, -0.2, 2.5);
  const Eigen::Vector2d u1 = project(K, p_l), u2 = project(K, T_cl * p_l);
  EXPECT_NEAR(epipolarDistance(F, u1, u2), 0.0, 1e-9);
  // Move u2 by 3 px along the line's unit normal [A, B] / |[A, B]|: the distance is exactly 3 px.
  const Eigen::Vector3d line = F * u1.homogeneous();
  const Eigen::Vector2d normal = line.head<2>().normalized();
  EXPECT_NEAR(epipolarDistance(F, u1, u2 + 3.0 * normal), 3.0, 1e-9);
  // Moving along the line leaves it at 0; scaling F changes nothing.
  const Eigen::Vector2d along(-normal.y(), normal.x());
  EXPECT_NEAR(epipolarDistance(F, u1, u2 + 10.0 * along), 0.0, 1e-9);
  EXPECT_NEAR(epipolarDistance(-7.0 * F, u1, u2 + 3.0 * normal), 3.0, 1e-9);
  // Agrees with OpenCV's epipolar lines for the same F.
  cv::Mat Fcv(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Fcv.at<double>(r, c) = F(r, c);
  std::vector<cv::Point2d> pts = {{u1.x(), u1.y()}};
  std::vector<cv::Vec3d> lines;
  cv::computeCorrespondEpilines(pts, 1, Fcv, lines);
  const Eigen::Vector2d q = u2 + Eigen::Vector2d(1.5, -2.0);
  EXPECT_NEAR(epipolarDistance(F, u1, q), std::abs(lines[0][0] * q.x() + lines[0][1] * q.y() + lines[0][2]), 1e-9);
}

// 200 static points and 60 points of an object moving 8 cm between the frames.
struct Correspondences {
  std::vector<cv::Point2f> last, current;
  std::vector<bool> moving;
};

Correspondences makeCorrespondences() {
  const Eigen::Matrix3d K = testK();
  const core::SE3 T_cl = testMotion();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(30, 610), v(30, 450), z(1.0, 4.0);
  std::normal_distribution<double> noise(0.0, 0.3);
  Correspondences c;
  for (int i = 0; i < 260; ++i) {
    const bool moving = i >= 200;
    Eigen::Vector3d p_l = K.inverse() * Eigen::Vector3d(u(rng), v(rng), 1.0) * z(rng);
    Eigen::Vector3d p_c = T_cl * p_l;
    if (moving) p_c += Eigen::Vector3d(0.0, 0.08, 0.03);
    const Eigen::Vector2d a = project(K, p_l), b = project(K, p_c);
    c.last.emplace_back(a.x() + noise(rng), a.y() + noise(rng));
    c.current.emplace_back(b.x() + noise(rng), b.y() + noise(rng));
    c.moving.push_back(moving);
  }
  return c;
}

TEST(FitFundamental, SeparatesStaticFromMovingPointsAndIsDeterministic) {
  const Correspondences c = makeCorrespondences();
  EpipolarOptions options;
  const FundamentalFit fit = fitFundamental(c.last, c.current, options);
  ASSERT_TRUE(fit.ok);
  EXPECT_GE(fit.final_inliers, 180);
  int static_flagged = 0, moving_flagged = 0;
  for (std::size_t i = 0; i < c.last.size(); ++i) {
    const double d = epipolarDistance(fit.F, {c.last[i].x, c.last[i].y}, {c.current[i].x, c.current[i].y});
    if (d > options.dynamic_threshold_px) (c.moving[i] ? moving_flagged : static_flagged)++;
  }
  EXPECT_EQ(static_flagged, 0);
  EXPECT_GT(moving_flagged, 45);  // a few moving points happen to slide along their epipolar lines
  const FundamentalFit again = fitFundamental(c.last, c.current, options);
  EXPECT_EQ(again.F, fit.F);
  EXPECT_EQ(again.final_inliers, fit.final_inliers);
}

TEST(FitFundamental, TooFewPointsIsNotOk) {
  const Correspondences c = makeCorrespondences();
  const std::vector<cv::Point2f> a(c.last.begin(), c.last.begin() + 10), b(c.current.begin(), c.current.begin() + 10);
  EXPECT_FALSE(fitFundamental(a, b, EpipolarOptions{}).ok);
  EpipolarOptions bad;
  bad.dynamic_threshold_px = 0.5;  // below the RANSAC threshold
  EXPECT_THROW(bad.check(), core::Error);
}

}  // namespace
}  // namespace amos::dynamic
