#include "amos/dynamic/frame_regions.h"

#include <gtest/gtest.h>

#include <utility>

namespace amos::dynamic {
namespace {

TEST(FrameRegions, PriorRegionsAreTheMasksConnectedComponents) {
  cv::Mat mask(30, 40, CV_8U, cv::Scalar(0));
  mask(cv::Rect(2, 2, 5, 5)).setTo(255);
  mask(cv::Rect(7, 7, 3, 3)).setTo(1);  // touches the first square diagonally: the same region (8-connectivity)
  mask(cv::Rect(30, 20, 5, 5)).setTo(255);
  const PriorRegions regions = findPriorRegions(mask);
  EXPECT_EQ(regions.count, 2);
  EXPECT_EQ(labelAt(regions.components, {3, 3}), labelAt(regions.components, {8, 8}));
  EXPECT_NE(labelAt(regions.components, {3, 3}), labelAt(regions.components, {32, 22}));
  EXPECT_EQ(labelAt(regions.components, {20, 15}), 0);
  EXPECT_EQ(findPriorRegions(cv::Mat(30, 40, CV_8U, cv::Scalar(0))).count, 0);
}

// 3 x 3 superpixel blocks of 10 x 10 px; clusters: the left column 0, the rest 1.
std::pair<SuperpixelSegmentation, cv::Mat> nineBlocks() {
  SuperpixelSegmentation segmentation;
  segmentation.labels.create(30, 30, CV_32S);
  cv::Mat clusters(30, 30, CV_32S);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 30; ++x) {
      segmentation.labels.at<int>(y, x) = (y / 10) * 3 + x / 10;
      clusters.at<int>(y, x) = x < 10 ? 0 : 1;
    }
  segmentation.superpixels.resize(9);
  return {segmentation, clusters};
}

TEST(FrameRegions, DecisionRegionsLeaveOutTheBorderBlocks) {
  const auto [segmentation, clusters] = nineBlocks();
  const DecisionRegions regions = findDecisionRegions(segmentation, clusters, 0);
  for (int s = 0; s < 9; ++s) EXPECT_EQ(regions.border[s], s != 4) << s;
  EXPECT_EQ(labelAt(regions.decision_map, {15, 15}), 1);
  EXPECT_EQ(labelAt(regions.decision_map, {5, 15}), -1);
  EXPECT_EQ(cv::countNonZero(regions.decision_map == 1), 100);
}

TEST(FrameRegions, PerTrackBorderRuleLeavesOutOnlyTheEdgeBand) {
  // With the per-track rule no block is a border block and only the 3 px band along the image edge is outside the
  // decision map.
  const auto [segmentation, clusters] = nineBlocks();
  const DecisionRegions regions = findEdgeDecisionRegions(segmentation, clusters, 3);
  for (int s = 0; s < 9; ++s) EXPECT_FALSE(regions.border[s]) << s;
  EXPECT_EQ(labelAt(regions.decision_map, {5, 15}), 0);   // a border block, 5 px from the edge: judged
  EXPECT_EQ(labelAt(regions.decision_map, {3, 15}), 0);   // the first pixel past the band
  EXPECT_EQ(labelAt(regions.decision_map, {2, 15}), -1);  // in the band
  EXPECT_EQ(labelAt(regions.decision_map, {15, 27}), -1);
  EXPECT_EQ(cv::countNonZero(regions.decision_map >= 0), 24 * 24);
  EXPECT_EQ(labelAt(clusters, {2, 15}), 0) << "the cluster map itself is left as it was";
  EXPECT_EQ(cv::countNonZero(findEdgeDecisionRegions(segmentation, clusters, 0).decision_map >= 0), 900);
}

TEST(FrameRegions, LookupsRoundToTheNearestPixelAndAreEmptyOutside) {
  cv::Mat labels(10, 10, CV_32S, cv::Scalar(0));
  labels.at<int>(3, 4) = 7;
  EXPECT_EQ(labelAt(labels, {4.4f, 2.6f}), 7);
  EXPECT_EQ(labelAt(labels, {4.6f, 2.6f}), 0);
  EXPECT_EQ(labelAt(labels, {-0.6f, 2.f}), -1);
  EXPECT_EQ(labelAt(labels, {9.6f, 2.f}), -1);
  EXPECT_EQ(labelAt(cv::Mat(), {1.f, 1.f}), -1);
  cv::Mat mask(10, 10, CV_8U, cv::Scalar(0));
  mask.at<uchar>(3, 4) = 1;
  EXPECT_TRUE(maskAt(mask, {3.6f, 3.4f}));
  EXPECT_FALSE(maskAt(mask, {3.4f, 3.4f}));
  EXPECT_FALSE(maskAt(mask, {10.f, 3.f}));
  EXPECT_FALSE(maskAt(cv::Mat(), {1.f, 1.f}));
}

}  // namespace
}  // namespace amos::dynamic
