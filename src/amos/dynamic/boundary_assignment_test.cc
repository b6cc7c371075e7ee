#include "amos/dynamic/boundary_assignment.h"

#include <gtest/gtest.h>

namespace amos::dynamic {
namespace {

// 120 x 100 cluster map: cluster 0 on the left (x < 60), cluster 1 on the right, cluster 2 a bottom strip
// (y >= 80) under both.
cv::Mat handMadeClusters() {
  cv::Mat map(100, 120, CV_32S, cv::Scalar(0));
  map(cv::Rect(60, 0, 60, 80)).setTo(1);
  map(cv::Rect(0, 80, 120, 20)).setTo(2);
  return map;
}

TEST(BoundaryAssignment, DynamicPointNearABorderGoesToTheNeighbourWithTheLargestError) {
  const cv::Mat map = handMadeClusters();
  const std::vector<double> error = {1.0, 5.0, 2.0};
  // 15 px left of the 0|1 border: cluster 1 is within 30 px and has the larger error.
  EXPECT_EQ(assignToNeighbourCluster({45, 30}, map, error, 30), 1);
  // 35 px from it: only its own cluster is in reach.
  EXPECT_EQ(assignToNeighbourCluster({25, 30}, map, error, 30), 0);
  // Near clusters 0 and 2 only (the 1 region is > 30 px away): 2 beats 0.
  EXPECT_EQ(assignToNeighbourCluster({10, 70}, map, error, 30), 2);
  // Inside the highest-error cluster it stays.
  EXPECT_EQ(assignToNeighbourCluster({70, 70}, map, error, 30), 1);
  // Radius 0 never moves a point.
  EXPECT_EQ(assignToNeighbourCluster({59, 30}, map, error, 0), 0);
  // Equal errors keep the point's own cluster.
  EXPECT_EQ(assignToNeighbourCluster({45, 30}, map, {3.0, 3.0, 3.0}, 30), 0);
}

TEST(BoundaryAssignment, IgnoredPixelsAreNeverChosen) {
  cv::Mat map = handMadeClusters();
  map(cv::Rect(60, 0, 60, 80)).setTo(-1);  // cluster 1 is a border block: left out of the decision
  const std::vector<double> error = {1.0, 5.0, 2.0};
  EXPECT_EQ(assignToNeighbourCluster({45, 30}, map, error, 30), 0);
  EXPECT_EQ(assignToNeighbourCluster({100, 30}, map, error, 10), -1);  // nothing but ignored pixels in reach
  EXPECT_EQ(assignToNeighbourCluster({100, 30}, map, error, 45), 0);   // reaches x = 59 (41 px), not y = 80
  EXPECT_EQ(assignToNeighbourCluster({100, 30}, map, error, 55), 2);   // now reaches the strip (50 px) too
}

TEST(BoundaryAssignment, BorderBlocksAreThoseTouchingTheImageEdge) {
  // 3 x 3 blocks of 10 x 10 px: only the centre block (label 4) does not touch the edge.
  cv::Mat labels(30, 30, CV_32S);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 30; ++x) labels.at<int>(y, x) = (y / 10) * 3 + x / 10;
  const std::vector<bool> border = borderSuperpixels(labels, 9, 0);
  for (int k = 0; k < 9; ++k) EXPECT_EQ(border[k], k != 4) << k;
  // A margin reaching into the centre block marks it too.
  EXPECT_TRUE(borderSuperpixels(labels, 9, 10)[4]);
  EXPECT_FALSE(borderSuperpixels(labels, 9, 9)[4]);
  // The decision map blanks the border blocks' pixels and keeps the rest.
  cv::Mat clusters(30, 30, CV_32S, cv::Scalar(7));
  const cv::Mat decision = decisionClusterMap(clusters, labels, border);
  EXPECT_EQ(decision.at<int>(15, 15), 7);
  EXPECT_EQ(decision.at<int>(0, 15), -1);
  EXPECT_EQ(cv::countNonZero(decision == 7), 100);
}

}  // namespace
}  // namespace amos::dynamic
