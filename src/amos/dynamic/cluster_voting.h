#pragma once
// The decision (paper III-C, last paragraphs): each epipolar violator votes for the cluster it belongs to after
// boundary reassignment (the cluster within Dynamic.Boundary.radius with the largest mean error,
// assignToNeighbourCluster); a candidate cluster with enough votes is dynamic,
// and so is a cluster confirmed under the refitted pose (pose_confirmation.h). Without F there are no violators and
// only the confirmation judges.
#include <opencv2/core.hpp>
#include <vector>

#include "amos/dynamic/front_end_types.h"
#include "amos/dynamic/frame_regions.h"
#include "amos/dynamic/reprojection_scoring.h"

namespace amos::dynamic {

struct ClusterVoting {
  std::vector<int> cluster_votes;     // per cluster
  std::vector<bool> dynamic_cluster;  // per cluster
};

// violators: current pixels of the tracks beyond the epipolar threshold (EpipolarEvidence::violators);
// decision_map: CV_32S cluster per pixel, -1 in border blocks (a violator there does not vote for a cluster);
// cluster_scores: Eq. 5 under the initial pose (candidate flags; mean_rho ranks the clusters for reassignment);
// confirmed: per cluster, confirmed under the refitted pose. Uses Dynamic.Boundary.radius and
// Dynamic.Epipolar.minDynamicPoints. Fills diag.confirmed_clusters and dynamic_clusters.
ClusterVoting voteClusters(const std::vector<cv::Point2f>& violators, const cv::Mat& decision_map,
                           const std::vector<ClusterScore>& cluster_scores, const std::vector<bool>& confirmed,
                           const DynamicOptions& options, DynamicDiagnostics& diag);

}  // namespace amos::dynamic
