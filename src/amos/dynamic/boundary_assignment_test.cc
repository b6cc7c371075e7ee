#include "amos/dynamic/boundary_assignment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <random>

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

// n x n blocks of 10 x 10 px, labelled row by row.
cv::Mat blockLabels(int n) {
  cv::Mat labels(10 * n, 10 * n, CV_32S);
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) labels.at<int>(y, x) = (y / 10) * n + x / 10;
  return labels;
}

Superpixel superpixel(float L, float depth, int cluster = 0) {
  Superpixel s;
  s.L = L;
  s.depth = depth;
  s.cluster = cluster;
  return s;
}

TEST(SuperpixelRegions, NeighboursShareAnEdge) {
  const auto neighbours = superpixelNeighbours(blockLabels(3), 9);
  EXPECT_EQ(neighbours[4], (std::vector<int>{1, 3, 5, 7}));
  EXPECT_EQ(neighbours[0], (std::vector<int>{1, 3}));  // diagonal blocks touch only at a corner
  EXPECT_EQ(neighbours[8], (std::vector<int>{5, 7}));
}

TEST(SuperpixelRegions, DissimilarityIsEq1WithoutPosition) {
  Superpixel a = superpixel(50, 2.0), b = superpixel(60, 2.2);
  b.A = 0, b.B = 0;
  EXPECT_NEAR(superpixelDissimilarity(a, b, 10.0, 0.1), 1.0 + 2.0, 1e-6);
  b.depth = 0;  // unknown depth: colour only
  EXPECT_NEAR(superpixelDissimilarity(a, b, 10.0, 0.1), 1.0, 1e-6);
  EXPECT_DOUBLE_EQ(superpixelDissimilarity(a, a, 10.0, 0.1), 0.0);
}

TEST(SuperpixelRegions, GrowingFollowsTheCheapestEdges) {
  // A chain 0-1-2-3-4 with L = 0, 1, 2, 50, 51 (and an isolated 5): seeded dynamic at 0 and static at 4, the
  // dynamic label takes 1 and 2, the static one 3; the big colour step between 2 and 3 is the border.
  std::vector<Superpixel> sp = {superpixel(0, 0), superpixel(1, 0), superpixel(2, 0),
                                superpixel(50, 0), superpixel(51, 0), superpixel(1, 0)};
  const std::vector<std::vector<int>> neighbours = {{1}, {0, 2}, {1, 3}, {2, 4}, {3}, {}};
  std::vector<RegionLabel> seeds(6, RegionLabel::kUnlabelled);
  seeds[0] = RegionLabel::kDynamic;
  seeds[4] = RegionLabel::kStatic;
  const std::vector<bool> anywhere(6, true);
  const auto labels = growRegions(sp, neighbours, seeds, anywhere, 1.0, 1.0);
  const std::vector<RegionLabel> expected = {RegionLabel::kDynamic, RegionLabel::kDynamic, RegionLabel::kDynamic,
                                             RegionLabel::kStatic,  RegionLabel::kStatic,  RegionLabel::kStatic};
  EXPECT_EQ(labels, expected);  // the unreachable 5 ends static
  // Where the dynamic label may not go, the static one takes over.
  std::vector<bool> restricted = anywhere;
  restricted[2] = false;
  const auto blocked = growRegions(sp, neighbours, seeds, restricted, 1.0, 1.0);
  EXPECT_EQ(blocked[1], RegionLabel::kDynamic);
  EXPECT_EQ(blocked[2], RegionLabel::kStatic);
}

TEST(SuperpixelRegions, OcclusionEdgesAreDepthStepsAlongTheSharedBorder) {
  // 3 x 3 blocks; the left column stands at 1 m in front of a 2 m wall, the right column is a slanted surface
  // (1 cm per pixel, about 0.5% of the depth: no step).
  const cv::Mat labels = blockLabels(3);
  cv::Mat depth(30, 30, CV_32F, cv::Scalar(2.f));
  depth.colRange(0, 10).setTo(1.f);
  for (int x = 20; x < 30; ++x) depth.col(x).setTo(2.f + 0.01f * (x - 19));
  depth.at<float>(15, 15) = 0.f;  // a hole changes nothing
  const auto neighbours = superpixelNeighbours(labels, 9);
  const auto occluding = occlusionEdges(labels, neighbours, depth, 0.05);
  auto edge = [&](int a, int b) {
    const auto it = std::find(neighbours[a].begin(), neighbours[a].end(), b);
    return static_cast<bool>(occluding[a][it - neighbours[a].begin()]);
  };
  EXPECT_TRUE(edge(0, 1));
  EXPECT_TRUE(edge(1, 0));
  EXPECT_TRUE(edge(4, 3));
  EXPECT_FALSE(edge(0, 3));  // same surface, one above the other
  EXPECT_FALSE(edge(4, 5));  // wall meets the slanted surface without a step
  EXPECT_FALSE(edge(5, 8));
  // The dynamic label does not cross an occlusion edge; the static one does.
  std::vector<Superpixel> sp(9, superpixel(50, 2.0));
  std::vector<RegionLabel> seeds(9, RegionLabel::kUnlabelled);
  seeds[0] = RegionLabel::kDynamic;
  seeds[8] = RegionLabel::kStatic;
  const std::vector<bool> anywhere(9, true);
  const auto free = growRegions(sp, neighbours, seeds, anywhere, 10.0, 0.1);
  const auto blocked = growRegions(sp, neighbours, seeds, anywhere, 10.0, 0.1, occluding);
  EXPECT_EQ(free[1], RegionLabel::kDynamic);  // equal costs: the lower id's offer (0 -> 1) comes first
  EXPECT_EQ(blocked[1], RegionLabel::kStatic);
  EXPECT_EQ(blocked[3], RegionLabel::kDynamic);  // down the same surface
  EXPECT_EQ(blocked[4], RegionLabel::kStatic);
}

// 5 x 5 blocks of 10 px; the outer ring is the image border. Cluster 0 = blocks 6, 7, 11, 12, cluster 1 = the rest
// (bordering cluster 0).
struct FiveByFiveBlocks {
  cv::Mat labels = blockLabels(5);
  std::vector<Superpixel> sp = [] {
    std::vector<Superpixel> v(25, superpixel(50, 2.0, 1));
    for (int s : {6, 7, 11, 12}) v[s].cluster = 0;
    return v;
  }();
  std::vector<std::vector<int>> neighbours = superpixelNeighbours(labels, 25);
  std::vector<bool> border = [] {
    std::vector<bool> v(25, true);
    for (int s : {6, 7, 8, 11, 12, 13, 16, 17, 18}) v[s] = false;
    return v;
  }();
  // Centre of block s.
  static cv::Point2f at(int s) { return cv::Point2f(10.f * (s % 5) + 5, 10.f * (s / 5) + 5); }
};

// The block scan on the working-resolution labels is the full-resolution scan of their upsampling, edge for edge:
// irregular superpixels (nearest of 40 random seeds), a depth per superpixel with steps of every size between
// them, a slope, holes and near-ties, at factors 2 and 3.
TEST(SuperpixelRegions, OcclusionEdgesOfBlocksEqualThoseOfTheUpsampledLabels) {
  std::mt19937 random(7);
  for (const int factor : {2, 3}) {
    const cv::Size small(53, 41);
    std::vector<cv::Point> seeds;
    std::uniform_int_distribution<int> sx(0, small.width - 1), sy(0, small.height - 1);
    for (int i = 0; i < 40; ++i) seeds.emplace_back(sx(random), sy(random));
    cv::Mat block_labels(small, CV_32S);
    for (int y = 0; y < small.height; ++y)
      for (int x = 0; x < small.width; ++x) {
        int best = 0;
        for (int i = 1; i < 40; ++i)
          if (cv::norm(seeds[i] - cv::Point(x, y)) < cv::norm(seeds[best] - cv::Point(x, y))) best = i;
        block_labels.at<int>(y, x) = best;
      }
    cv::Mat labels;
    cv::resize(block_labels, labels, cv::Size(), factor, factor, cv::INTER_NEAREST);
    std::uniform_real_distribution<float> base(1.f, 4.f), hole(0.f, 1.f);
    std::vector<float> level(40);
    for (float& z : level) z = base(random);
    cv::Mat depth(labels.size(), CV_32F);
    for (int y = 0; y < depth.rows; ++y)
      for (int x = 0; x < depth.cols; ++x)
        depth.at<float>(y, x) = hole(random) < 0.05f ? 0.f : level[labels.at<int>(y, x)] + 0.002f * x;
    const auto neighbours = superpixelNeighbours(block_labels, 40);
    ASSERT_EQ(neighbours, superpixelNeighbours(labels, 40));
    const auto full = occlusionEdges(labels, neighbours, depth, 0.05);
    EXPECT_EQ(occlusionEdgesOfBlocks(block_labels, factor, neighbours, depth, 0.05), full) << "factor " << factor;
    int edges = 0;
    for (const auto& row : full) edges += static_cast<int>(std::count(row.begin(), row.end(), true));
    EXPECT_GT(edges, 10);  // the comparison is not between two empty answers
  }
}

TEST(SuperpixelRegions, TracksSeedByTheirMotion) {
  // Cluster 0 is dynamic and moves by (3, 0) px; cluster 1 is static.
  const FiveByFiveBlocks b;
  const auto& [labels, sp, neighbours, border] = b;
  const SuperpixelSegmentation segmentation{labels, {}, sp};
  const std::vector<bool> dynamic_cluster = {true, false};
  auto at = &FiveByFiveBlocks::at;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<TrackEvidence> tracks = {
      {at(6), Eigen::Vector2d(3.0, 0.0), 0.1},   // moves with its dynamic cluster
      {at(7), Eigen::Vector2d(3.1, 0.1), 0.1},
      {at(11), Eigen::Vector2d(2.9, 0.0), 0.1},
      {at(12), Eigen::Vector2d(0.1, 0.0), 0.1},  // still, inside the dynamic cluster: background caught by it
      {at(8), Eigen::Vector2d(1.6, 0.0), 0.1},   // below static_px, but nearer the cluster's motion than zero
      {at(13), Eigen::Vector2d(0.2, 0.0), 0.1},  // still
      {at(16), std::nullopt, 5.0},               // no depth, off its epipolar line, next to the mover
      {at(0), Eigen::Vector2d(3.0, 0.0), 0.1},   // border block: no vote
      {at(18), std::nullopt, inf},               // nothing known
  };
  const auto seeds = seedSuperpixels(segmentation, neighbours, border, dynamic_cluster, tracks, {2.0, 2.0});
  const RegionLabel D = RegionLabel::kDynamic, S = RegionLabel::kStatic, U = RegionLabel::kUnlabelled;
  EXPECT_EQ(seeds[6], D);
  EXPECT_EQ(seeds[7], D);
  EXPECT_EQ(seeds[11], D);
  EXPECT_EQ(seeds[12], S);
  EXPECT_EQ(seeds[8], D);
  EXPECT_EQ(seeds[13], S);
  EXPECT_EQ(seeds[16], D);
  EXPECT_EQ(seeds[0], U);
  EXPECT_EQ(seeds[18], U);
  // Two opposite votes leave a superpixel unlabelled.
  tracks.push_back({at(13), Eigen::Vector2d(3.0, 0.0), 0.1});
  EXPECT_EQ(seedSuperpixels(segmentation, neighbours, border, dynamic_cluster, tracks, {2.0, 2.0})[13], U);
  // With no static cluster dynamic, a moving track outside any dynamic cluster only abstains.
  const auto none = seedSuperpixels(segmentation, neighbours, border, {false, false}, tracks, {2.0, 2.0});
  EXPECT_EQ(none[6], U);
  EXPECT_EQ(none[12], S);
  // A dynamic cluster whose own tracks all look still (judged by violators outside it) gets no dynamic seed.
  const std::vector<TrackEvidence> still = {{at(12), Eigen::Vector2d(0.1, 0.0), 0.1}};
  const auto quiet = seedSuperpixels(segmentation, neighbours, border, dynamic_cluster, still, {2.0, 2.0});
  EXPECT_EQ(quiet[6], U);
  EXPECT_EQ(quiet[12], S);
}

TEST(SuperpixelRegions, TracksOutsideTheDynamicClustersSeedOnlyWhenAskedAndInPairs) {
  // Nothing dynamic. Block 7 holds two tracks moving by themselves, block 17 one, block 13 two moving and three
  // still ones.
  const FiveByFiveBlocks b;
  const auto& [labels, sp, neighbours, border] = b;
  const SuperpixelSegmentation segmentation{labels, {}, sp};
  const std::vector<bool> dynamic_cluster = {false, false};
  auto at = &FiveByFiveBlocks::at;
  const Eigen::Vector2d moving(3.0, 0.0), still(0.1, 0.0);
  const std::vector<TrackEvidence> tracks = {
      {at(7), moving, 0.1},  {at(7), moving, 0.1},  {at(17), moving, 0.1}, {at(13), moving, 0.1},
      {at(13), moving, 0.1}, {at(13), still, 0.1},  {at(13), still, 0.1},  {at(13), still, 0.1},
      {at(16), std::nullopt, 5.0},  // an epipolar violator alone: the epipolar test needs a candidate region
      {at(16), std::nullopt, 5.0},
  };
  const RegionLabel D = RegionLabel::kDynamic, S = RegionLabel::kStatic, U = RegionLabel::kUnlabelled;
  const auto off = seedSuperpixels(segmentation, neighbours, border, dynamic_cluster, tracks, {2.0, 2.0});
  EXPECT_EQ(off[7], U);
  EXPECT_EQ(off[13], S);
  const auto on = seedSuperpixels(segmentation, neighbours, border, dynamic_cluster, tracks, {2.0, 2.0}, {true, 2});
  EXPECT_EQ(on[7], D);
  EXPECT_EQ(on[17], U);  // one track may be an LK slip
  EXPECT_EQ(on[13], S);  // outvoted
  EXPECT_EQ(on[16], U);
  const auto three = seedSuperpixels(segmentation, neighbours, border, dynamic_cluster, tracks, {2.0, 2.0}, {true, 3});
  EXPECT_EQ(three[7], U);
}

}  // namespace
}  // namespace amos::dynamic
