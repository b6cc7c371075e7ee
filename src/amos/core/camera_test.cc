#include "amos/core/camera.h"

#include <gtest/gtest.h>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/testing/test_camera.h"

namespace amos::core {
namespace {

CameraIntrinsics fr3() { return testing::testIntrinsics(); }

TEST(Camera, ProjectInvertsBackProject) {
  PinholeCamera cam(fr3());
  const Eigen::Vector3d p = cam.backProject(100.5, 400.25, 2.5);
  const Eigen::Vector2d uv = cam.project(p);
  EXPECT_NEAR(uv.x(), 100.5, 1e-9);
  EXPECT_NEAR(uv.y(), 400.25, 1e-9);
  EXPECT_NEAR(p.z(), 2.5, 1e-12);
}

TEST(Camera, RejectsNonPositiveFocalLengthNamingTheMember) {
  CameraIntrinsics c = fr3();
  c.fy = 0;
  EXPECT_THROW(PinholeCamera{c}, InvalidOption);
  try {
    c.check();
    FAIL() << "expected an error";
  } catch (const InvalidOption& e) {
    EXPECT_EQ(e.field().address, &c.fy);  // how the settings reader finds the key, Camera.fy
    EXPECT_STREQ(e.what(), "fy must be > 0, got 0");
  }
}

TEST(Camera, UndistortIsIdentityWithoutDistortion) {
  PinholeCamera cam(fr3());
  const auto out = cam.undistort({{10.f, 20.f}});
  EXPECT_FLOAT_EQ(out[0].x, 10.f);
  EXPECT_FLOAT_EQ(out[0].y, 20.f);
}

TEST(Camera, UndistortMovesCornerPixelsWithFr1Distortion) {
  const CameraIntrinsics c = testing::tumFr1Intrinsics();
  PinholeCamera cam(c);
  const auto out = cam.undistort({{0.f, 0.f}, {static_cast<float>(c.cx), static_cast<float>(c.cy)}});
  EXPECT_GT(std::abs(out[0].x) + std::abs(out[0].y), 1.0);  // the corner moves
  EXPECT_NEAR(out[1].x, c.cx, 1e-3);                   // the principal point does not
}

TEST(Camera, DistortInvertsUndistort) {
  PinholeCamera fr1(testing::tumFr1Intrinsics());
  const std::vector<cv::Point2f> raw{{5.f, 7.f}, {320.f, 240.f}, {600.f, 30.f}, {100.f, 470.f}};
  const std::vector<cv::Point2f> back = fr1.distort(fr1.undistort(raw));
  ASSERT_EQ(back.size(), raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) {
    EXPECT_NEAR(back[i].x, raw[i].x, 0.05) << i;
    EXPECT_NEAR(back[i].y, raw[i].y, 0.05) << i;
  }
  CameraIntrinsics none = testing::tumFr1Intrinsics();
  none.k1 = none.k2 = none.p1 = none.p2 = none.k3 = 0;
  EXPECT_EQ(PinholeCamera(none).distort(raw), raw);
}

}  // namespace
}  // namespace amos::core
