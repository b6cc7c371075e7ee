#include "amos/dynamic/cluster_voting.h"

#include <gtest/gtest.h>

namespace amos::dynamic {
namespace {

// 120 x 100 decision map: cluster 0 on the left (x < 60), cluster 1 on the right; the bottom strip (y >= 80) is a
// border block (-1).
cv::Mat votingLeftRightClusters() {
  cv::Mat map(100, 120, CV_32S, cv::Scalar(0));
  map(cv::Rect(60, 0, 60, 80)).setTo(1);
  map(cv::Rect(0, 80, 120, 20)).setTo(-1);
  return map;
}

ClusterScore score(double mean_rho, bool candidate) {
  ClusterScore s;
  s.mean_rho = mean_rho;
  s.candidate = candidate;
  return s;
}

// Votes stay in the violator's own cluster (radius 0) and a region needs two of them.
DynamicOptions noReassignment() {
  DynamicOptions options;
  options.boundary.search_radius_px = 0;
  options.epipolar.min_dynamic_points = 2;
  return options;
}

// voteClusters on votingLeftRightClusters().
ClusterVoting vote(const std::vector<cv::Point2f>& violators, const std::vector<ClusterScore>& scores,
                   const std::vector<bool>& confirmed, DynamicDiagnostics& diag,
                   const DynamicOptions& options = noReassignment()) {
  return voteClusters(violators, votingLeftRightClusters(), scores, confirmed, options, diag);
}

TEST(ClusterVoting, ACandidateNeedsVotesAConfirmedClusterDoesNot) {
  DynamicDiagnostics diag;
  // Two candidates: cluster 0 with two votes is dynamic, cluster 1 with one is not.
  const ClusterVoting by_votes =
      vote({{10, 10}, {20, 30}, {100, 10}}, {score(5, true), score(5, true)}, {false, false}, diag);
  EXPECT_EQ(by_votes.cluster_votes, (std::vector<int>{2, 1}));
  EXPECT_EQ(by_votes.dynamic_cluster, (std::vector<bool>{true, false}));
  // Cluster 0 has three votes but is no candidate; cluster 1 has none but was confirmed under the refitted pose.
  const ClusterVoting by_confirmation =
      vote({{10, 10}, {20, 30}, {30, 50}}, {score(0.1, false), score(5, false)}, {false, true}, diag);
  EXPECT_EQ(by_confirmation.cluster_votes, (std::vector<int>{3, 0}));
  EXPECT_EQ(by_confirmation.dynamic_cluster, (std::vector<bool>{false, true}));
  EXPECT_EQ(diag.dynamic_clusters, 2);  // one per call
  EXPECT_EQ(diag.confirmed_clusters, 1);
}

TEST(ClusterVoting, AViolatorNearABorderVotesForTheNeighbourWithTheLargerError) {
  DynamicOptions options = noReassignment();
  options.boundary.search_radius_px = 30;
  DynamicDiagnostics diag;
  // 10 and 5 px left of the 0|1 border: both go to cluster 1, whose mean error is larger.
  const ClusterVoting voting =
      vote({{50, 10}, {55, 40}}, {score(1, true), score(5, true)}, {false, false}, diag, options);
  EXPECT_EQ(voting.cluster_votes, (std::vector<int>{0, 2}));
  EXPECT_EQ(voting.dynamic_cluster, (std::vector<bool>{false, true}));
}

TEST(ClusterVoting, ViolatorsInBorderBlocksDoNotVote) {
  DynamicDiagnostics diag;
  const ClusterVoting voting =
      vote({{10, 90}, {20, 95}, {100, 10}}, {score(5, true), score(5, true)}, {false, false}, diag);
  EXPECT_EQ(voting.cluster_votes, (std::vector<int>{0, 1}));  // the two in the strip vote for no cluster
  EXPECT_EQ(diag.dynamic_clusters, 0);
}

TEST(ClusterVoting, WithoutViolatorsOnlyTheConfirmationJudges) {
  DynamicDiagnostics diag;
  const ClusterVoting voting = vote({}, {score(5, true), score(5, true)}, {true, false}, diag);
  EXPECT_EQ(voting.cluster_votes, (std::vector<int>{0, 0}));
  EXPECT_EQ(voting.dynamic_cluster, (std::vector<bool>{true, false}));
}

}  // namespace
}  // namespace amos::dynamic
