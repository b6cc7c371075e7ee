#include "amos/dynamic/geometric_clustering.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

#include "amos/core/error.h"

namespace amos::dynamic {
namespace {

struct Blob {
  float x, y, depth;
};

// Five tight groups; groups 0 and 1 overlap in the image and differ only in depth, so only the depth dimension
// can separate them.
std::vector<ClusterPoint> makeBlobs(std::vector<int>& truth) {
  const std::vector<Blob> blobs = {
      {200, 200, 1.0f}, {205, 195, 3.0f}, {500, 100, 2.0f}, {100, 400, 2.5f}, {520, 400, 1.5f}};
  std::mt19937 rng(3);
  std::normal_distribution<float> pixel(0.f, 15.f), metre(0.f, 0.05f);
  std::vector<ClusterPoint> points;
  for (int i = 0; i < 40; ++i)
    for (std::size_t b = 0; b < blobs.size(); ++b) {
      points.push_back({blobs[b].x + pixel(rng), blobs[b].y + pixel(rng), blobs[b].depth + metre(rng)});
      truth.push_back(static_cast<int>(b));
    }
  return points;
}

TEST(GeometricClustering, KMeansRecoversSyntheticClustersIncludingOnesSeparatedOnlyByDepth) {
  std::vector<int> truth;
  const std::vector<ClusterPoint> points = makeBlobs(truth);
  ClusteringOptions options;
  options.num_clusters = 5;
  const std::vector<int> labels = kmeansClusters(points, {640, 480}, options);
  ASSERT_EQ(labels.size(), points.size());
  // Every true group maps to exactly one label and the mapping is one-to-one.
  std::map<int, std::set<int>> labels_of_truth;
  for (std::size_t i = 0; i < labels.size(); ++i) labels_of_truth[truth[i]].insert(labels[i]);
  std::set<int> used;
  for (const auto& [group, set] : labels_of_truth) {
    EXPECT_EQ(set.size(), 1u) << "group " << group << " was split";
    used.insert(*set.begin());
  }
  EXPECT_EQ(used.size(), 5u);
}

TEST(GeometricClustering, IsDeterministicForAFixedSeed) {
  std::vector<int> truth;
  const std::vector<ClusterPoint> points = makeBlobs(truth);
  ClusteringOptions options;
  options.num_clusters = 7;  // more clusters than groups: the split depends on the seeding
  EXPECT_EQ(kmeansClusters(points, {640, 480}, options), kmeansClusters(points, {640, 480}, options));
}

TEST(GeometricClustering, PointsWithoutDepthClusterByPosition) {
  std::vector<int> truth;
  std::vector<ClusterPoint> points = makeBlobs(truth);
  // Group 4's points lose their depth; they must still join one cluster of their own.
  for (std::size_t i = 0; i < points.size(); ++i)
    if (truth[i] == 4) points[i].depth = 0;
  ClusteringOptions options;
  options.num_clusters = 5;
  const std::vector<int> labels = kmeansClusters(points, {640, 480}, options);
  std::set<int> of_group4, of_others;
  for (std::size_t i = 0; i < labels.size(); ++i) (truth[i] == 4 ? of_group4 : of_others).insert(labels[i]);
  EXPECT_EQ(of_group4.size(), 1u);
  EXPECT_EQ(of_others.count(*of_group4.begin()), 0u);
}

TEST(GeometricClustering, FewerPointsThanClustersAndEmptyInput) {
  ClusteringOptions options;
  options.num_clusters = 16;
  EXPECT_TRUE(kmeansClusters({}, {640, 480}, options).empty());
  const std::vector<int> labels = kmeansClusters({{10, 10, 1}, {600, 400, 2}, {10, 400, 0}}, {640, 480}, options);
  EXPECT_EQ(std::set<int>(labels.begin(), labels.end()).size(), 3u);
  options.num_clusters = 0;
  EXPECT_THROW(options.check(), core::Error);
}

TEST(GeometricClustering, ClusterMapFollowsTheSuperpixelLabels) {
  SuperpixelSegmentation seg;
  seg.labels = cv::Mat(4, 6, CV_32S);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) seg.labels.at<int>(y, x) = x / 2;  // three vertical stripes
  seg.superpixels.resize(3);
  seg.superpixels[0].x = 0.5f, seg.superpixels[0].depth = 1.f;
  seg.superpixels[1].x = 2.5f, seg.superpixels[1].depth = 1.f;
  seg.superpixels[2].x = 4.5f, seg.superpixels[2].depth = 5.f;
  ClusteringOptions options;
  options.num_clusters = 2;
  const cv::Mat map = clusterSuperpixels(seg, options);
  EXPECT_EQ(clusterCount(seg), 2);
  EXPECT_EQ(seg.superpixels[0].cluster, seg.superpixels[1].cluster);
  EXPECT_NE(seg.superpixels[0].cluster, seg.superpixels[2].cluster);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) EXPECT_EQ(map.at<int>(y, x), seg.superpixels[x / 2].cluster);
}

}  // namespace
}  // namespace amos::dynamic
