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

namespace amos::dynamic {

struct DepthEvidenceOptions {
  // Dynamic.Depth.enabled: the depth evidence takes part in the decisions (geometry and full modes).
  bool enabled = false;
  // Dynamic.Depth.sampleStep: every step-th pixel in x and y. 4 gives 160x120 samples on 640x480 (~40 per
  // superpixel of S ~ 26 px), enough for a median whose standard error is a sixth of the noise, at ~1 ms.
  int sample_step_px = 4;
  // Dynamic.Depth.noiseBase / noiseQuadratic / noiseOffset: the sensor's axial noise sigma(z) = base + quadratic
  // (z - offset)^2 [m] (Nguyen et al. 2012, Kinect v1; the synthetic sensor uses the same model).
  double noise_base_m = 0.0012;
  double noise_quadratic = 0.0019;
  double noise_offset_m = 0.4;
  // Dynamic.Depth.maxDepth: samples farther than this in either frame do not count. The specified range of the
  // structured-light sensors (Kinect v1 4 m, Xtion 3.5 m): beyond it the error is no longer the noise model's
  // Gaussian (disparity steps of 5 cm and more at 4-5 m, multipath), and TUM fr2/desk's static background at 4-5.6 m
  // was the only thing its 10-frame comparison found moving.
  double max_depth_m = 4.0;
  // Dynamic.Depth.sigmas: a superpixel moves when its median residual is this many of its standard errors from
  // zero. 4: on ~300 static superpixels per frame a Gaussian statistic passes 4 sigma once in ~50 frames.
  double sigmas = 4.0;
  // Dynamic.Depth.minResidual: ... and at least this far [m]. A pose error of 1 mrad (half a pixel at f ~ 540 px)
  // shifts a point at 3 m by 3 mm sideways, which on a surface seen at 60-70 deg from its normal reads as 5-8 mm
  // of depth: 1 cm stays above that.
  double min_residual_m = 0.01;
  // Dynamic.Depth.minRelativeResidual: ... and at least this share of the depth. A real structured-light sensor's
  // error is not only noise: its depth carries a bias that varies over the image by ~1 % of the depth (the "donut"
  // of a Kinect's depth distortion), which a surface seen at other pixels in the other frame reads as motion (TUM
  // fr2/desk, static: the floor at 2-3 m; geometry mode marks 6.4 % of its pixels with 0 and 2.3 % with 0.02,
  // against 2.1 % without the depth evidence). 0 for an ideal sensor.
  double min_relative_residual = 0.02;
  // Dynamic.Depth.minSamples: valid samples a superpixel needs to be judged (a median of fewer is noise).
  int min_samples = 8;
  // Dynamic.Depth.violationSigmas: a sample violates free space when the last frame measured a surface farther
  // than its lifted point by this many sigma (and minResidual): the point stands where the last frame saw empty
  // space, which no static point can (a static point revealed by the motion lies behind what hid it: the opposite
  // sign). This is the leading edge of a mover crossing the view, whose flat inside shows no depth change. 3: a
  // sample of the static world passes it in ~0.1 % of the cases.
  double violation_sigmas = 3.0;
  // Dynamic.Depth.violationShare: a superpixel moves when at least this share of its samples violate free space
  // (and at least minViolations of them). 0.2: a mover advancing 5 px per frame into a superpixel of S ~ 26 px.
  double violation_share = 0.2;
  int min_violations = 4;  // Dynamic.Depth.minViolations
  // Dynamic.Depth.clusterShare: a decision cluster is dynamic when at least this share of its valid samples lies in
  // moving superpixels (the mask then grows over the cluster from them, boundary_assignment.h) ...
  double cluster_share = 0.3;
  // Dynamic.Depth.unscoredClusterSuperpixels: ... or when it holds at least this many moving superpixels and too
  // few tracks for Eq. 5 to score it: the inside of a trackless mover (a plain fabric chair crossing the view)
  // shows no depth change, only its leading edge does, and nothing says that the rest of its cluster is static.
  int unscored_cluster_superpixels = 2;
  // Dynamic.Depth.baselineFrames: the current depth is also compared with that of the frame this many frames back
  // (FrontEndInput::baseline_depth), and a superpixel moves when either comparison says so. Against the last
  // frame alone a mover must shift by minResidual (1 cm) in 33 ms, 0.3 m/s; over 10 frames (0.33 s) 3 cm/s will
  // do: a door easing into its stops, a chair starting to roll (2-3 px per frame at 1 m). The price: a mover that
  // stops stays marked for up to this many frames. 0 = the last frame only.
  int baseline_frames = 10;
  // Dynamic.Depth.baselineRelativeResidual: minRelativeResidual for that comparison. The sensor's depth bias varies
  // over the image, and over 10 frames a surface moves across more of it than over one: TUM fr2/desk's static
  // floor and walls at 3.5-3.8 m read 2 % (6-8 cm) farther than 10 frames before. 0.04: twice the one-frame floor.
  double baseline_relative_residual = 0.04;
  void check() const;
  // Axial noise at depth z [m].
  double sigma(double z) const { return noise_base_m + noise_quadratic * (z - noise_offset_m) * (z - noise_offset_m); }
};

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

// The lifted samples of the current frame (pose T_cw) against the depth of another frame (last_depth, CV_32F, pose
// T_cw_last), per superpixel (count labels). free_space_only: only a positive median (the surface now stands in
// front of what the other frame saw) moves a superpixel; for a comparison over many frames, where a negative one is
// mostly background that a mover has uncovered meanwhile (over one frame that is a strip, too thin to move a
// median).
DepthEvidence superpixelDepthEvidence(const LiftedDepthSamples& current, const cv::Mat& last_depth,
                                      const core::SE3& T_cw_last, const core::SE3& T_cw,
                                      const core::PinholeCamera& camera, int count, double depth_edge_ratio,
                                      const DepthEvidenceOptions& options, bool free_space_only = false);
// The same from the current depth image (liftDepthSamples, then the comparison).
DepthEvidence superpixelDepthEvidence(const cv::Mat& depth, const cv::Mat& last_depth, const core::SE3& T_cw_last,
                                      const core::SE3& T_cw, const core::PinholeCamera& camera,
                                      const DepthSampleGrid& grid, const cv::Mat& labels, int count,
                                      double depth_edge_ratio, const DepthEvidenceOptions& options,
                                      bool free_space_only = false);

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
DepthEvidence frameDepthEvidence(const cv::Mat& depth, const core::SE3& T_cw, const cv::Mat& last_depth,
                                 const core::SE3& T_cw_last, const cv::Mat& baseline_depth,
                                 const core::SE3& T_cw_baseline, const core::PinholeCamera& camera,
                                 const DepthSampleGrid& grid, const SuperpixelSegmentation& segmentation,
                                 double depth_edge_ratio, const DepthEvidenceOptions& options);

// Marks dynamic (in dynamic_cluster, per cluster) the clusters that depthMovingClusters finds moving, a cluster
// counting as scored when Eq. 5 had min_points tracks for it (cluster_scores). Returns how many it added.
int addDepthMovingClusters(const DepthEvidence& evidence, const SuperpixelSegmentation& segmentation,
                           const std::vector<ClusterScore>& cluster_scores, int min_points,
                           const DepthEvidenceOptions& options, std::vector<bool>& dynamic_cluster);

}  // namespace amos::dynamic
