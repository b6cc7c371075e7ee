#include "amos/dynamic/cluster_voting.h"

#include "amos/dynamic/boundary_assignment.h"

namespace amos::dynamic {

ClusterVoting voteClusters(const std::vector<cv::Point2f>& violators, const cv::Mat& decision_map,
                           const std::vector<ClusterScore>& cluster_scores, const std::vector<bool>& confirmed,
                           const DynamicOptions& options, DynamicDiagnostics& diag) {
  const int num_clusters = static_cast<int>(cluster_scores.size());
  // Boundary reassignment gives a violator to the neighbouring cluster with the largest mean error (Eq. 5).
  std::vector<double> cluster_error(num_clusters);
  for (int c = 0; c < num_clusters; ++c) cluster_error[c] = cluster_scores[c].mean_rho;
  ClusterVoting voting;
  voting.cluster_votes.assign(num_clusters, 0);
  for (const cv::Point2f& p : violators) {
    if (labelAt(decision_map, p) < 0) continue;  // in a border block
    const int c = assignToNeighbourCluster(p, decision_map, cluster_error, options.boundary.search_radius_px);
    if (c >= 0) ++voting.cluster_votes[c];
  }
  const int min_votes = options.epipolar.min_dynamic_points;
  voting.dynamic_cluster.assign(num_clusters, false);
  for (int c = 0; c < num_clusters; ++c) {
    voting.dynamic_cluster[c] = (cluster_scores[c].candidate && voting.cluster_votes[c] >= min_votes) || confirmed[c];
    if (confirmed[c]) ++diag.confirmed_clusters;
    if (voting.dynamic_cluster[c]) ++diag.dynamic_clusters;
  }
  return voting;
}

}  // namespace amos::dynamic
