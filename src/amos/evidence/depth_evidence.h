#pragma once
// Depth evidence for movers that carry no corner tracks (issue 16: a dark fabric chair gets 0-3 of the 500 corners,
// so the paper's Eq. 5 has nothing to score it by). The depth image needs no texture: under the static-world
// hypothesis every current pixel with depth, lifted to 3D and moved into the last frame by the relative pose, must
// land on the surface the last frame measured there. This is the paper's reprojection test (Eq. 6: back-project with
// depth, reproject with the pose) with the depth coordinate as the residual instead of a tracked pixel.
//
// Per sample (every sampleStep-th pixel): r = z_last(p') - z of the lifted point in the last camera, where p' is the
// pixel it projects to. Samples whose depth, in either frame, jumps within +-4 px (depth edges: flying pixels, and
// a pose error of a pixel there changes the surface read) do not count. Per superpixel: the median residual, so
// that a superpixel moves only when most of it moved (a strip of revealed background along a mover, or the
// disocclusion at a static depth edge, cannot move it), judged against the sensor's axial noise (Nguyen, Izadi,
// Lovell 2012: sigma(z) = 0.0012 + 0.0019 (z - 0.4)^2 m for a Kinect v1 / Xtion) as the standard error of a median
// of n samples, and against a floor for what a pose error of a fraction of a pixel does on oblique surfaces.
// A superpixel also moves when a fifth of its samples violate free space (they stand where the other frame saw
// empty space: the leading edge of a flat mover crossing the view, whose inside shows no depth change).
// DynamicFrontEnd compares with the last frame and, for movers too slow for one frame, with the frame
// baselineFrames back (free space only: over many frames a receding surface is mostly background uncovered
// meanwhile). Moving superpixels seed the mask (mask_building.h) and make their clusters dynamic
// (depthMovingClusters). Measurements: docs/experiments/front-end-defaults.md.
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/depth_slic.h"
#include "amos/dynamic/reprojection_scoring.h"
#include "amos/dynamic/evidence_options.h"
#include "amos/evidence/evidence_frames.h"

namespace amos::evidence {

using dynamic::ClusterScore;
using dynamic::DepthEvidenceOptions;
using dynamic::ReprojectionOptions;
using dynamic::Superpixel;
using dynamic::SuperpixelSegmentation;


// The sample pixels of a camera's image and their undistorted normalised coordinates, computed once per camera.
class DepthSampleGrid {
 public:
  DepthSampleGrid() = default;
  DepthSampleGrid(const core::PinholeCamera& camera, int step_px);
  const std::vector<cv::Point>& pixels() const { return pixels_; }
  const std::vector<cv::Point2d>& normalised() const { return normalised_; }  // (x/z, y/z)

 private:
  std::vector<cv::Point> pixels_;
  std::vector<cv::Point2d> normalised_;
};

struct SuperpixelDepth {
  int samples = 0;           // valid samples in the superpixel
  int violations = 0;        // samples violating free space (see violation_sigmas)
  double median_m = 0;       // median residual z_last(p') - z (0 with fewer than min_samples)
  double threshold_m = 0;    // what |median_m| had to exceed
  double standard_error_m = 0;  // of the median, from the sensor noise
  double depth_m = 0;           // mean depth of the samples
  bool moving = false;
  // With free_space_only: the median says that the surface now lies behind what the other frame saw (below
  // -threshold_m), which alone does not make the superpixel move (see combineDepthEvidence).
  bool receded = false;
};

struct DepthEvidence {
  std::vector<SuperpixelDepth> superpixels;  // per superpixel label
  int samples = 0;                           // valid samples in the frame
  int moving_superpixels = 0;
};

// Offset of the depth-edge test [px] (smoothDepthAt).
inline constexpr int kDepthEdgeOffset = 4;

// Depth at raw pixel (x, y) when it is valid and none of the four neighbours kDepthEdgeOffset away lies across a
// depth edge (differs by more than ratio times the depth); else 0, also within kDepthEdgeOffset of the image's edge.
float smoothDepthAt(const cv::Mat& depth, int x, int y, double ratio);

// The current frame's side of a comparison, the same for every frame it is compared with: the samples of `grid`
// with a valid depth (CV_32F metres, 0 = none) that lies on no depth edge (a neighbour 4 px away differing by more
// than depth_edge_ratio, Dynamic.Reprojection.depthEdgeRatio) and within options.max_depth_m, lifted into the
// current camera, with their superpixel label (labels: CV_32S, the depth's size).
struct LiftedDepthSamples {
  std::vector<int> labels;
  std::vector<Eigen::Vector3d> points_c;
};
LiftedDepthSamples liftDepthSamples(const cv::Mat& depth, const DepthSampleGrid& grid, const cv::Mat& labels,
                                    double depth_edge_ratio, const DepthEvidenceOptions& options);

// How two depths are compared: the camera, Dynamic.Reprojection.depthEdgeRatio, the options. free_space_only: only
// a positive median (the surface now stands in front of what the other frame saw) moves a superpixel; for a
// comparison over many frames, where a negative one is mostly background that a mover has uncovered meanwhile (over
// one frame that is a strip, too thin to move a median).
struct DepthComparison {
  const core::PinholeCamera& camera;
  double depth_edge_ratio;
  const DepthEvidenceOptions& options;
  bool free_space_only = false;
};

// The lifted samples of the current frame (pose T_cw) against the depth of another frame (CV_32F, the camera's
// size), per superpixel (count labels).
DepthEvidence superpixelDepthEvidence(const LiftedDepthSamples& current, int count, const core::SE3& T_cw,
                                      const PosedDepth& other, const DepthComparison& comparison);
// The same from the current depth image (liftDepthSamples, then the comparison).
DepthEvidence superpixelDepthEvidence(const PosedDepth& current, const PosedDepth& other, const DepthSampleGrid& grid,
                                      const SuperpixelLabels& superpixels, const DepthComparison& comparison);

// Per superpixel, the evidence of either comparison (a: the last frame's, b: a baseline frame's, free space only):
// moving when either says so, or when b says that the surface receded and a that it is still receding now (its
// median at least two standard errors below zero): background uncovered by a mover some frames ago is at rest
// now, a door swinging away is not. The larger sample and violation counts, the median of the one that moves
// (else of a).
DepthEvidence combineDepthEvidence(const DepthEvidence& a, const DepthEvidence& b);

// Per cluster, whether at least options.cluster_share of its valid samples lie in moving superpixels, or it holds
// options.unscored_cluster_superpixels moving superpixels and scored[c] is false (Eq. 5 had too few tracks).
// cluster_of_superpixel: each superpixel's cluster (0 .. num_clusters-1).
std::vector<bool> depthMovingClusters(const DepthEvidence& evidence, const std::vector<int>& cluster_of_superpixel,
                                      const std::vector<bool>& scored, int num_clusters,
                                      const DepthEvidenceOptions& options);

// The front end's two comparisons (depth_evidence.h's header): the current frame (depth, pose T_cw) against the
// last one, and, when baseline_depth is not empty, against the baseline frame with its own relative floor, free
// space only, combined (combineDepthEvidence).
struct DepthFrames {
  PosedDepth current, last;
  PosedDepth baseline;  // its depth empty without a baseline frame
};
DepthEvidence frameDepthEvidence(const DepthFrames& frames, const DepthSampleGrid& grid,
                                 const SuperpixelSegmentation& segmentation, const DepthComparison& comparison);

// Per cluster (as many as cluster_scores), whether depthMovingClusters finds it moving, a cluster counting as scored
// when Eq. 5 had min_points tracks for it.
std::vector<bool> depthMovingClusters(const DepthEvidence& evidence, const SuperpixelSegmentation& segmentation,
                                      const std::vector<ClusterScore>& cluster_scores, int min_points,
                                      const DepthEvidenceOptions& options);

}  // namespace amos::evidence
