#pragma once
// The dynamic mask from the decisions (paper III-C; boundary_assignment.h): per superpixel in and around the
// dynamic clusters (Dynamic.Boundary.superpixelMask), so that it follows the mover's outline rather than the
// clusters' blobs, else the whole dynamic clusters.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "amos/dynamic/boundary_assignment.h"
#include "amos/dynamic/candidate_scoring.h"
#include "amos/dynamic/cluster_voting.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/front_end_types.h"
#include "amos/dynamic/epipolar_evidence.h"
#include "amos/dynamic/frame_regions.h"
#include "amos/dynamic/geometric_clustering.h"
#include "amos/dynamic/pose_confirmation.h"

namespace amos::dynamic {

// Seeds of the surface growth (Dynamic.RigidMovers.growOverSurface): per superpixel, those that follow a rigid mover, and those the growth from them may enter at all (empty = any): a
// mover speaks only for its own region (rigid_movers.h, superpixelsNearMovers), so its plain surface lies there too.
struct SurfaceSeeds {
  std::vector<bool> seeds;
  std::vector<bool> within;
};

// The evidence sources' contribution to the mask, per superpixel (evidence_source.h; empty vectors without them):
// depth_moving from the depth evidence and baseline_moving from the long-baseline tracks (or a rigid mover) seed it
// as dynamic; baseline_points (long-baseline points per superpixel) and surface_seeds bound the growth over a
// mover's plain surface (Dynamic.RigidMovers.growOverSurface).
struct SuperpixelEvidence {
  std::vector<bool> depth_moving;
  std::vector<bool> baseline_moving;
  std::vector<int> baseline_points;
  SurfaceSeeds surface_seeds;
};

// Sets to 255 the pixels of mask (CV_8U) whose label in label_map (CV_32S, same size, each label an index into
// marked) is marked.
void markLabelledPixels(const cv::Mat& label_map, const std::vector<bool>& marked, cv::Mat& mask);

// What the tracks say about the superpixels they end in (seedSuperpixels), without the tracks that would seed the
// wrong one: those whose LK window holds an occlusion edge or whose depth jumps between the frames, and those off
// their superpixel's surface. residuals: per track under the judged pose; epipolar_px: per track;
// static_bar_px: the residual a static track stays below (PoseConfirmation::static_bar_px). Uses
// Dynamic.Reprojection.depthEdgeRatio and half of Dynamic.LK.window.
struct JudgedTracks {
  const std::vector<PointTrack>& tracks;
  const TrackPoints& lifted;                                      // their Eq. 6 points or depth intervals
  const std::vector<std::optional<Eigen::Vector2d>>& residuals;  // per track, under the judged pose
  const std::vector<double>& epipolar_px;                         // per track
};
std::vector<TrackEvidence> seedingEvidence(const JudgedTracks& judged, const cv::Mat& last_depth,
                                           const cv::Mat& depth, const SuperpixelSegmentation& segmentation,
                                           double static_bar_px, const DynamicOptions& options);

// The tracks' part of the seeding: their evidence, the static bar of their residuals, and whether a track may seed
// a superpixel outside the dynamic clusters (Dynamic.Boundary.seedOutsideClusters with a refitted pose).
struct TrackSeeds {
  const std::vector<TrackEvidence>& evidence;
  double static_bar_px;
  bool seed_outside;
};

// Per superpixel, whether it is dynamic: seeds from the evidence (seedSuperpixels; also away from the dynamic
// clusters with seed_outside), then seeded region growing (growRegions) that may enter a superpixel as dynamic only
// in a dynamic cluster or from a dynamic seed, and never across an occlusion edge of depth (CV_32F metres).
// `graph`: the superpixels' adjacency and occlusion edges when computed ahead (null: computed here).
// `moving`, the evidence sources' (SuperpixelEvidence): `depth_moving`, per superpixel, whether its depth moved
// (evidence/depth_evidence.h; empty = no depth evidence): such a superpixel that the tracks leave unlabelled is a
// dynamic seed (border superpixels excepted). `baseline_moving`: per superpixel, whether its points moved over the
// long baseline (evidence/baseline_tracks.h; empty = none): such a superpixel is a dynamic seed whatever its
// one-frame votes say (border superpixels excepted). `baseline_points`: per superpixel, how many long-baseline points
// lie on it (empty = none). `surface_seeds` (none = empty): the dynamic label may also enter, outside the dynamic
// clusters and within their `within` superpixels, the superpixels that neither a track nor a long-baseline point
// measured and that are reached from a seed through non-occlusion borders, each step between superpixels at most
// Dynamic.BaselineTracks.growDissimilarity apart (surfaceFromMovingSeeds).
// The frame's superpixels, its depth (CV_32F metres) and, when computed ahead, their graph (null: computed here).
struct SuperpixelFrame {
  const SuperpixelSegmentation& segmentation;
  const cv::Mat& depth;
  const SuperpixelGraph* graph = nullptr;
};
// Per superpixel, whether it is a border block; per cluster, whether it is dynamic.
struct ClusterVerdicts {
  const std::vector<bool>& border;
  const std::vector<bool>& dynamic_cluster;
};
std::vector<bool> dynamicSuperpixels(const SuperpixelFrame& frame, const ClusterVerdicts& verdicts,
                                     const TrackSeeds& tracks, const DynamicOptions& options,
                                     const SuperpixelEvidence& moving = {});

// The superpixels that the dynamic label may enter beyond the dynamic clusters under growOverSurface (see
// dynamicSuperpixels): breadth-first from `moving.seeds` (the rigid movers' superpixels) over unmeasured, non-border
// superpixels; only into the `moving.within` ones (empty = any); each step at most similarity.max_dissimilarity.
struct SurfaceSimilarity {
  double colour_scale;       // Dynamic.Superpixel.colourScale
  double depth_scale_m;      // Dynamic.Superpixel.depthScale
  double max_dissimilarity;  // Dynamic.BaselineTracks.growDissimilarity
};
std::vector<bool> surfaceFromMovingSeeds(const std::vector<Superpixel>& superpixels, const SuperpixelGraph& graph,
                                         const std::vector<RegionLabel>& seeds, const std::vector<bool>& border,
                                         const SurfaceSeeds& moving, const std::vector<int>& baseline_points,
                                         const SurfaceSimilarity& similarity);

struct DynamicMask {
  cv::Mat mask;                          // CV_8U, 255 = dynamic
  std::vector<bool> dynamic_superpixel;  // per superpixel (per-superpixel mask only, else empty)
};

// The earlier stages' results the mask is built from (references, valid during one process() call).
struct MaskStages {
  const FrontEndInput& in;
  const std::vector<PointTrack>& tracks;
  const GeometricPartition& partition;
  const DecisionRegions& regions;
  const CandidateScoring& candidates;
  const PoseConfirmation& confirmation;
  const EpipolarEvidence& epipolar;
  const ClusterVoting& voting;
};

// The geometric stage's mask (the caller masks the prior regions itself). moving: the evidence sources' seeds and
// surface growth (empty without; see dynamicSuperpixels). Fills diag.dynamic_superpixels.
DynamicMask buildDynamicMask(const MaskStages& stages, const SuperpixelEvidence& moving, const DynamicOptions& options,
                             DynamicDiagnostics& diag);

}  // namespace amos::dynamic
