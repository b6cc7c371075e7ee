#pragma once
// Boundary handling of the geometric module (paper III-C, last paragraphs): epipolar violators tend to sit on
// the borders of moving objects, where the cluster under the point may be the static background. Such a point
// is given to the cluster around it (within ~30 px) whose mean reprojection error is the largest. Superpixel
// blocks touching the image border take no part in the decision.
// The same boundary problem at the scale of the mask: a cluster is a compact blob of ~140 px that need not follow
// the mover's outline, so a dynamic cluster also covers background and a mover split between clusters is partly
// missed, while depth-SLIC superpixels do follow it. The mask is therefore decided per superpixel: superpixels
// whose tracks move with the dynamic cluster (or stay static) seed the two labels, and seeded region growing
// over the superpixel adjacency graph (Adams & Bischof 1994, cost = Eq. 1 without the position term) labels the
// superpixels without tracks after their most similar labelled neighbour.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <cstdint>
#include <optional>
#include <vector>

#include "amos/dynamic/depth_slic.h"

namespace amos::dynamic {

struct BoundaryOptions {
  // Dynamic.Boundary.radius: the paper's 30 px, about one superpixel step at 640x480 (S ~ 32 px for 300
  // superpixels): far enough to reach the cluster on the other side of the border the point sits on, not so far
  // as to jump over a whole cluster (~140 px cells).
  int search_radius_px = 30;
  // Dynamic.Boundary.borderMargin: a superpixel is a border block when it comes within this many pixels of the
  // image edge. 0 = touching the edge, as in the paper: those blocks are cut by the image frame, so their
  // corners track worst (LK windows leave the image, content enters and leaves the view).
  int border_margin_px = 0;
  // Dynamic.Boundary.borderBlocks: true = the paper's rule, whole superpixel blocks touching the image edge (within
  // borderMargin) take no part in the decisions. false = the rule is applied per track: only a track whose last or
  // current pixel lies within half an LK window (+1 px) of the edge abstains (DynamicFrontEnd::edgeBand), i.e. one
  // whose finest-level window was cut by the frame, which is the reason the paper gives for the rule; border blocks
  // are judged like any other. A mover near the camera on the floor (a pushed box, a chair) or entering the view
  // touches the image edge for most of its time in view, and a superpixel is ~32 px wide, so the block rule discards
  // its tracks up to ~40 px in; the forward-backward check already rejects the tracks that the frame spoiled.
  bool border_blocks = true;
  // Dynamic.Boundary.superpixelMask: true = the mask is decided per superpixel inside and around the dynamic
  // clusters (seeded region growing, see above); false = the mask is the union of the dynamic clusters.
  bool superpixel_mask = true;
  // Dynamic.Boundary.seedOutsideClusters: with the per-superpixel mask and a successful pose refit, a superpixel
  // outside the dynamic clusters and their neighbours whose own tracks move under the refitted pose (at least
  // Dynamic.Epipolar.minDynamicPoints of them above the confirmation threshold, more than those below it) is a
  // dynamic seed too. A deformable walker is split across the position-only clusters, and where it is a minority
  // of a cluster that cluster's mean stays low; its superpixels' own tracks still move.
  bool seed_outside_clusters = true;
  void check() const;
};

// Marks the superpixels (labels CV_32S in [0, count)) that reach within margin_px of the image edge.
std::vector<bool> borderSuperpixels(const cv::Mat& superpixel_labels, int count, int margin_px);

// The cluster map used for decisions: the per-pixel cluster map with the border blocks set to -1.
cv::Mat decisionClusterMap(const cv::Mat& cluster_map, const cv::Mat& superpixel_labels,
                           const std::vector<bool>& border_superpixels);

// The cluster a dynamic point at pixel p counts for: among the clusters found within radius_px of p in
// decision_map (CV_32S, -1 = ignored), the one with the largest cluster_error (ties: the cluster under p, then
// the lower id). Returns -1 when the disc holds no cluster.
int assignToNeighbourCluster(cv::Point2f p, const cv::Mat& decision_map, const std::vector<double>& cluster_error,
                             int radius_px);

// Neighbours of every superpixel (labels CV_32S in [0, count), 4-connectivity), each list sorted.
std::vector<std::vector<int>> superpixelNeighbours(const cv::Mat& superpixel_labels, int count);

// For every neighbour pair of superpixelNeighbours (same layout): whether most of their shared border is a depth
// step, i.e. depths a few pixels apart across it (depth CV_32F metres, 0 = unknown) differ by more than `ratio`
// of the nearer one. A mover seen against the scene behind it is bounded by such occlusion edges (except where it
// rests on a surface, where colour has to separate it); a slanted surface (a few mm per pixel) is not one.
std::vector<std::vector<bool>> occlusionEdges(const cv::Mat& superpixel_labels,
                                              const std::vector<std::vector<int>>& neighbours, const cv::Mat& depth,
                                              double ratio);

// The same for a label map given at 1/factor of the depth's resolution, whose nearest-neighbour upsampling (every
// label a factor x factor block) is the map the edges are asked for: identical result, factor^2 fewer pixels scanned.
std::vector<std::vector<bool>> occlusionEdgesOfBlocks(const cv::Mat& block_labels, int factor,
                                                      const std::vector<std::vector<int>>& neighbours,
                                                      const cv::Mat& depth, double ratio);

// How unlike two superpixels are: Eq. 1 without the position term, |Lab difference| / colour_scale +
// |depth difference| / depth_scale_m (the depth term only when both have depth).
double superpixelDissimilarity(const Superpixel& a, const Superpixel& b, double colour_scale, double depth_scale_m);

enum class RegionLabel : std::int8_t { kUnlabelled = -1, kStatic = 0, kDynamic = 1 };

// Seeded region growing: starting from the seeds, repeatedly the unlabelled superpixel adjacent to a labelled one
// with the smallest dissimilarity to it takes that neighbour's label. A superpixel with may_be_dynamic false
// never takes the dynamic label (it can still be reached by the static one), and the dynamic label does not cross
// an occlusion edge (occluding, laid out as neighbours; empty = none): a trackless background surface that looks
// like the mover (the desk behind a cardboard box) is not part of it. Superpixels no label reaches are static.
// Deterministic (ties broken by superpixel id).
std::vector<RegionLabel> growRegions(const std::vector<Superpixel>& superpixels,
                                     const std::vector<std::vector<int>>& neighbours, std::vector<RegionLabel> seeds,
                                     const std::vector<bool>& may_be_dynamic, double colour_scale,
                                     double depth_scale_m, const std::vector<std::vector<bool>>& occluding = {});

// What one last->current track says about the superpixel it ends in.
struct TrackEvidence {
  cv::Point2f pixel;                        // current-frame pixel (raw)
  std::optional<Eigen::Vector2d> residual;  // reprojection residual [px] under the judged pose; none without depth
  double epipolar_px = 0;                   // distance from its epipolar line [px] (infinity when there was no F)
};

// Seeds for growRegions from the tracks, given the dynamic clusters. A track counts only for the dynamic clusters
// of its own superpixel's cluster or, outside them, of the clusters bordering it (where the mover's remainder
// lies when a cluster border cuts it). There it votes dynamic when it moves with such a cluster (its residual
// nearer the cluster's median residual than to zero, the cluster moving by at least static_px), moves by itself
// (residual >= static_px) or breaks the epipolar constraint (> epipolar_px); everywhere it votes static when its
// residual is below static_px. A superpixel takes the majority of its votes (ties and no votes: unlabelled);
// border superpixels are not seeded. A dynamic cluster without a dynamic seed of its own (judged by violators on
// its border, see assignToNeighbourCluster) is reached only by growth from its neighbours' seeds: whole-cluster
// marking is what the per-superpixel mask is there to avoid. labels: superpixel map (CV_32S);
// superpixels[i].cluster: each one's cluster.
// Seeding away from the dynamic clusters (see seedSuperpixels).
struct SeedOptions {
  // Tracks outside every dynamic cluster and its neighbours also vote dynamic when they move by themselves
  // (residual >= static_px under a refitted pose). Needs a pose the movers did not bias: only then is a residual
  // above the noise bar motion rather than pose error.
  bool seed_outside_zones = false;
  // Votes such a superpixel needs (and more than its static votes): two independent tracks, as for an epipolar
  // region (one may be an LK slip).
  int min_outside_votes = 2;
};
// The bars a track's evidence is read against: a residual below static_px votes static, an epipolar distance or
// a residual beyond epipolar_px votes dynamic.
struct SeedBars {
  double static_px = 0, epipolar_px = 0;
};

std::vector<RegionLabel> seedSuperpixels(const SuperpixelSegmentation& segmentation,
                                         const std::vector<std::vector<int>>& neighbours,
                                         const std::vector<bool>& border, const std::vector<bool>& dynamic_cluster,
                                         const std::vector<TrackEvidence>& tracks, const SeedBars& bars,
                                         const SeedOptions& options = {});

// What the mask building needs of a frame's superpixels that depends on the frame alone: their adjacency
// (superpixelNeighbours) and which shared borders are occlusion edges (occlusionEdges). A pipeline that prepares
// frames ahead computes it with the partition, off the sequential path (GeometricPartition::graph).
struct SuperpixelGraph {
  std::vector<std::vector<int>> neighbours;
  std::vector<std::vector<bool>> occlusion_edges;
};
SuperpixelGraph superpixelGraph(const SuperpixelSegmentation& segmentation, const cv::Mat& depth,
                                double depth_edge_ratio);

}  // namespace amos::dynamic
