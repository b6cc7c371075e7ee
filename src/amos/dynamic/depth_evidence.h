#pragma once
// Depth evidence for movers that carry no corner tracks (issue 16: a dark fabric chair gets 0-3 of the 500 corners,
// so the paper's Eq. 5 has nothing to score it by). The depth image needs no texture: under the static-world
// hypothesis every current pixel with depth, lifted to 3D and moved into the last frame by the relative pose, must
// land on the surface the last frame measured there. This is the paper's reprojection test (Eq. 6: back-project with
// depth, reproject with the pose) with the depth coordinate as the residual instead of a tracked pixel.
//
// Per sample (every sampleStep-th pixel): r = z_last(p') - z of the lifted point in the last camera, where p' is the
// pixel it projects to. Samples whose depth, in either frame, jumps within +-2 px (depth edges: flying pixels, and
// a pose error of a pixel there changes the surface read) do not count. Per superpixel: the median residual, so
// that a superpixel moves only when most of it moved (a strip of revealed background along a mover, or the
// disocclusion at a static depth edge, cannot move it), judged against the sensor's axial noise (Nguyen, Izadi,
// Lovell 2012: sigma(z) = 0.0012 + 0.0019 (z - 0.4)^2 m for a Kinect v1 / Xtion) as the standard error of a median
// of n samples, and against a floor for what a pose error of a fraction of a pixel does on oblique surfaces.
#include <opencv2/core.hpp>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"

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
  // Dynamic.Depth.sigmas: a superpixel moves when its median residual is this many of its standard errors from
  // zero. 4: on ~300 static superpixels per frame a Gaussian statistic passes 4 sigma once in ~50 frames.
  double sigmas = 4.0;
  // Dynamic.Depth.minResidual: ... and at least this far [m]. A pose error of 1 mrad (half a pixel at f ~ 540 px)
  // shifts a point at 3 m by 3 mm sideways, which on a surface seen at 60-70 deg from its normal reads as 5-8 mm
  // of depth: 1 cm stays above that.
  double min_residual_m = 0.01;
  // Dynamic.Depth.minSamples: valid samples a superpixel needs to be judged (a median of fewer is noise).
  int min_samples = 8;
  // Dynamic.Depth.clusterShare: a decision cluster is dynamic when at least this share of its valid samples lies in
  // moving superpixels (the mask then grows over the cluster from them, boundary_assignment.h).
  double cluster_share = 0.3;
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
  double median_m = 0;       // median residual z_last(p') - z (0 with fewer than min_samples)
  double threshold_m = 0;    // what |median_m| had to exceed
  bool moving = false;
};

struct DepthEvidence {
  std::vector<SuperpixelDepth> superpixels;  // per superpixel label
  int samples = 0;                           // valid samples in the frame
  int moving_superpixels = 0;
};

// depth, last_depth: CV_32F metres (0 = none), raw pixels of the camera; labels: CV_32S superpixel label of every
// pixel (0 .. count-1). T_cw_last, T_cw: the poses of the two frames. depth_edge_ratio: a neighbour 2 px away whose
// depth differs by more than this share marks a depth edge (Dynamic.Reprojection.depthEdgeRatio).
DepthEvidence superpixelDepthEvidence(const cv::Mat& depth, const cv::Mat& last_depth, const core::SE3& T_cw_last,
                                      const core::SE3& T_cw, const core::PinholeCamera& camera,
                                      const DepthSampleGrid& grid, const cv::Mat& labels, int count,
                                      double depth_edge_ratio, const DepthEvidenceOptions& options);

// Per cluster, whether at least options.cluster_share of its valid samples lie in moving superpixels.
// cluster_of_superpixel: each superpixel's cluster (0 .. num_clusters-1).
std::vector<bool> depthMovingClusters(const DepthEvidence& evidence, const std::vector<int>& cluster_of_superpixel,
                                      int num_clusters, const DepthEvidenceOptions& options);

}  // namespace amos::dynamic
