#include "amos/dense/frame_preparation.h"

#include <gtest/gtest.h>

#include "amos/core/error.h"
#include "amos/dense/test_room.h"

namespace amos::dense {
namespace {

FrameImages flatWall(const core::CameraIntrinsics& k, float depth) {
  return {cv::Mat(k.height, k.width, CV_32F, cv::Scalar(depth)), cv::Mat(k.height, k.width, CV_8UC3, cv::Scalar(90, 90, 90)),
          cv::Mat()};
}

TEST(FramePreparation, LeavesOutTheDynamicPixelsWithTheirMargin) {
  const core::CameraIntrinsics k = testing::roomCamera();
  DenseOptions o;
  o.scale = 1.0;
  o.mask_margin_px = 3;
  FrameImages f = flatWall(k, 2.0f);
  f.dynamic_mask = cv::Mat::zeros(k.height, k.width, CV_8U);
  f.dynamic_mask(cv::Rect(50, 40, 20, 20)).setTo(255);
  const PreparedFrame p = FramePreparer(k, o).prepare(f);
  EXPECT_EQ(p.depth.at<float>(50, 60), 0.0f);      // inside the mask
  EXPECT_EQ(p.depth.at<float>(50, 48), 0.0f);      // 2 px outside it: the margin
  EXPECT_EQ(p.depth.at<float>(50, 45), 2.0f);      // 5 px outside it
  EXPECT_EQ(p.removed.at<float>(50, 60), 2.0f);    // kept apart as removed
  EXPECT_EQ(p.removed.at<float>(50, 45), 0.0f);
}

// The images are the run's (shared, not copied): preparing a frame in the fusion thread must not write them. The
// scaled path dilated the mask into a header of the caller's, which made `run --dense --deterministic` differ
// from run to run.
TEST(FramePreparation, LeavesTheCallersImagesUnchanged) {
  const core::CameraIntrinsics k = testing::roomCamera();
  DenseOptions o;
  o.scale = 0.5;
  FrameImages f = flatWall(k, 2.0f);
  f.dynamic_mask = cv::Mat::zeros(k.height, k.width, CV_8U);
  f.dynamic_mask(cv::Rect(50, 40, 20, 20)).setTo(255);
  const cv::Mat mask = f.dynamic_mask.clone(), depth = f.depth.clone(), bgr = f.bgr.clone();
  FramePreparer(k, o).prepare(f);
  EXPECT_EQ(cv::countNonZero(f.dynamic_mask != mask), 0);
  EXPECT_EQ(cv::countNonZero(f.depth != depth), 0);
  EXPECT_EQ(cv::norm(f.bgr, bgr, cv::NORM_INF), 0);
}

TEST(FramePreparation, LeavesOutDepthDiscontinuitiesAndReadingsOutOfRange) {
  const core::CameraIntrinsics k = testing::roomCamera();
  DenseOptions o;
  o.scale = 1.0;
  o.edge_margin_px = 1;
  o.max_depth = 4.0;
  FrameImages f = flatWall(k, 3.0f);
  f.depth(cv::Rect(0, 0, 80, k.height)).setTo(1.5f);  // a foreground object on the left half
  f.depth(cv::Rect(0, 0, 10, 10)).setTo(5.0f);        // beyond maxDepth
  const PreparedFrame p = FramePreparer(k, o).prepare(f);
  for (int u = 78; u <= 81; ++u) EXPECT_EQ(p.depth.at<float>(60, u), 0.0f) << "u " << u;  // the step, +-1 px
  EXPECT_EQ(p.depth.at<float>(60, 77), 1.5f);
  EXPECT_EQ(p.depth.at<float>(60, 82), 3.0f);
  EXPECT_EQ(p.depth.at<float>(60, 70), 1.5f);
  EXPECT_EQ(p.depth.at<float>(60, 90), 3.0f);
  EXPECT_EQ(p.depth.at<float>(5, 5), 0.0f);
  // A slanted wall (0.5 % depth step between neighbours) is no discontinuity.
  for (int u = 0; u < k.width; ++u) f.depth.col(u).setTo(2.0f + 0.01f * u);
  const PreparedFrame slanted = FramePreparer(k, o).prepare(f);
  EXPECT_EQ(cv::countNonZero(slanted.depth(cv::Rect(5, 5, 150, 110))), 150 * 110);
}

TEST(FramePreparation, ScalesImagesAndIntrinsics) {
  const core::CameraIntrinsics k = testing::roomCamera();
  DenseOptions o;
  o.scale = 0.5;
  const FramePreparer preparer(k, o);
  const PreparedFrame p = preparer.prepare(flatWall(k, 2.0f));
  EXPECT_EQ(p.depth.cols, 80);
  EXPECT_EQ(p.bgr.rows, 60);
  EXPECT_DOUBLE_EQ(preparer.intrinsics().fx, 55);
  EXPECT_DOUBLE_EQ(preparer.intrinsics().cx, 39.5);  // the centre pixel stays the centre pixel
}

TEST(FramePreparation, RefusesImagesOfAnotherSize) {
  const core::CameraIntrinsics k = testing::roomCamera();
  FrameImages f = flatWall(k, 2.0f);
  f.depth = cv::Mat(10, 10, CV_32F, cv::Scalar(1.0f));
  EXPECT_THROW(FramePreparer(k, DenseOptions{}).prepare(f), core::Error);
}

}  // namespace
}  // namespace amos::dense
