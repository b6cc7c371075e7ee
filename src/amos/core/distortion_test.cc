#include "amos/core/distortion.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <vector>

namespace amos::core {
namespace {

// TUM fr2's lens (the strongest of the datasets used here) and Bonn's.
RadialTangential fr2() { return {0.231222, -0.784899, -0.003257, -0.000105, 0.917205}; }
RadialTangential bonn() { return {0.039903, -0.099343, -0.000730, -0.000144, 0}; }

// Normalised points over a 640x480 image with f = 520: |x| up to 0.62, |y| up to 0.46, corners included.
std::vector<Eigen::Vector2d> grid() {
  std::vector<Eigen::Vector2d> out;
  for (double x = -0.62; x <= 0.621; x += 0.124) {
    for (double y = -0.46; y <= 0.461; y += 0.092) out.emplace_back(x, y);
  }
  return out;
}

TEST(RadialTangential, MatchesOpenCvProjectPoints) {
  for (const RadialTangential& d : {fr2(), bonn()}) {
    std::vector<cv::Point3d> rays;
    for (const Eigen::Vector2d& p : grid()) rays.emplace_back(p.x(), p.y(), 1.0);
    std::vector<cv::Point2d> expected;
    const cv::Mat dist = (cv::Mat_<double>(1, 5) << d.k1, d.k2, d.p1, d.p2, d.k3);
    cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), cv::Mat::eye(3, 3, CV_64F), dist, expected);
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const Eigen::Vector2d got = d.distort({rays[i].x, rays[i].y});
      EXPECT_NEAR(got.x(), expected[i].x, 1e-12);
      EXPECT_NEAR(got.y(), expected[i].y, 1e-12);
    }
  }
}

TEST(RadialTangential, JacobianMatchesCentralDifferences) {
  const double h = 1e-6;
  for (const RadialTangential& d : {fr2(), bonn()}) {
    for (const Eigen::Vector2d& p : grid()) {
      Eigen::Matrix2d J;
      d.distort(p, &J);
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector2d e = Eigen::Vector2d::Unit(k) * h;
        const Eigen::Vector2d numeric = (d.distort(p + e) - d.distort(p - e)) / (2 * h);
        EXPECT_NEAR(J(0, k), numeric.x(), 1e-8);
        EXPECT_NEAR(J(1, k), numeric.y(), 1e-8);
      }
    }
  }
  // Without distortion the Jacobian is the identity, exactly.
  Eigen::Matrix2d J;
  RadialTangential{}.distort({0.3, -0.2}, &J);
  EXPECT_EQ(J, Eigen::Matrix2d::Identity());
}

TEST(RadialTangential, UndistortInvertsDistort) {
  for (const RadialTangential& d : {fr2(), bonn()}) {
    for (const Eigen::Vector2d& raw : grid()) {
      const Eigen::Vector2d xn = d.undistort(raw);
      EXPECT_LT((d.distort(xn) - raw).norm(), 1e-13);
    }
  }
  const Eigen::Vector2d p(0.3, -0.2);
  EXPECT_EQ(RadialTangential{}.undistort(p), p);
  EXPECT_EQ(RadialTangential{}.distort(p), p);
}

}  // namespace
}  // namespace amos::core
