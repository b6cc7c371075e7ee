#pragma once
// The options of the evidence sources added after the paper (src/amos/evidence/: depth evidence, long-baseline
// tracks, rigid movers). They live here, beside DynamicOptions, because the front end's options carry them; the
// sources that read them live in the evidence module.
#include <cmath>

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
  // of a Kinect's depth distortion), which a surface seen at other pixels in the other frame reads as motion
  // (measurements: docs/experiments/front-end-defaults.md). 0 for an ideal sensor.
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
  // over the image, and over 10 frames a surface moves across more of it than over one (the figures:
  // docs/experiments/front-end-defaults.md). 0.04: twice the one-frame floor.
  double baseline_relative_residual = 0.04;
  void check() const;
  // Axial noise at depth z [m].
  double sigma(double z) const { return noise_base_m + noise_quadratic * (z - noise_offset_m) * (z - noise_offset_m); }
};

struct BaselineTrackOptions {
  // Dynamic.BaselineTracks.enabled: the long-baseline test takes part in the decisions (geometry and full modes;
  // needs Dynamic.Depth.baselineFrames > 1, the history it compares with).
  bool enabled = false;
  // Dynamic.BaselineTracks.sigmas: a point moves when its residual exceeds this many noise scales of the points
  // (as Dynamic.Reprojection.confirmSigmas for one frame) ...
  double sigmas = 5.0;
  // Dynamic.BaselineTracks.minMotion: ... and this many pixels. Twice the one-frame floor (1 px): over ten frames
  // the appearance of a surface changes more (perspective, lighting), and LK's error grows with it.
  double min_motion_px = 2.0;
  // Dynamic.BaselineTracks.minVotes: moving points a superpixel or a cluster needs: two independent points, as for
  // an epipolar region (one may be an LK slip).
  int min_votes = 2;
  // Dynamic.BaselineTracks.clusterShare: share of a decision cluster's points that must move for the whole cluster
  // to become dynamic (the mask then grows over it from the moving superpixels). A half: a cluster that straddles a
  // mover and the static surface beside it (a door leaf in front of its wall) is dynamic when the mover holds most of
  // its points.
  double cluster_share = 0.5;
  // Dynamic.BaselineTracks.growDissimilarity: the largest step of the surface growth from the rigid movers'
  // superpixels (Dynamic.RigidMovers.growOverSurface, mask_building.h): Eq. 1 without the position term
  // (superpixelDissimilarity); 1 = a colour difference of colourScale Lab units, or a depth step of depthScale (10 cm), the unit of SLIC's own distance.
  double grow_dissimilarity = 1.0;
  void check() const;
};

struct RigidMoverOptions {
  // Dynamic.RigidMovers.enabled: the test takes part in the decisions. It fits the long-baseline tracks' moving
  // points, so it acts only with Dynamic.BaselineTracks.enabled (a settings file may switch either alone).
  bool enabled = false;
  // Dynamic.RigidMovers.minInliers: moving long-baseline points one rigid motion must explain. EPnP needs 4 and
  // 6 fix a rigid motion; 8 leaves two over, so that a few LK slips on the static world (0-11 of ~110 points per
  // frame beyond the bar on TUM fr2/desk, scattered) do not make a mover.
  int min_inliers = 8;
  // Dynamic.RigidMovers.inlierPx: a point follows a motion when it is reprojected within this many pixels of where
  // LK found it in the baseline frame: the long-baseline bar's floor (Dynamic.BaselineTracks.minMotion, 2 px), LK's
  // error over ten frames. A mover's motion must also move its inliers by more than this from the static world's.
  double inlier_px = 2.0;
  // Dynamic.RigidMovers.maxMovers: rigid motions fitted one after the other on the moving points left over.
  int max_movers = 3;
  // Dynamic.RigidMovers.sampleStep: the samples lie on a grid of this step [px] (as the depth evidence's).
  int sample_step_px = 4;
  // Dynamic.RigidMovers.minSeparation: a sample decides only where the two hypotheses put it this many pixels
  // apart in the baseline frame; closer, a 3x3 patch's difference is interpolation, not evidence.
  double min_separation_px = 1.0;
  // Dynamic.RigidMovers.intensityMargin: a hypothesis wins a sample when its mean absolute difference over the 3x3
  // patch is lower by this many grey levels: sensor noise of 2-3 grey levels gives a patch mean that varies by
  // well under 1, and ten frames of shading and resampling by 1-3 more.
  double intensity_margin = 6.0;
  // Dynamic.RigidMovers.minSamples: votes a superpixel needs (and twice the static ones) to move: three independent
  // patches (4 px apart, the 3x3 patches do not overlap).
  int min_samples = 3;
  // Dynamic.RigidMovers.regionReach: a mover speaks only for the samples within this many pixels of the box around
  // its points (the paper's boundary reach, Dynamic.Boundary.radius: about one superpixel).
  int region_reach_px = 30;
  // Dynamic.RigidMovers.minGradient: a sample needs at least this RMS intensity gradient [grey levels per px] along
  // the direction that separates the two hypotheses, over 7x7 px (windowStructure): at 4 the image noise of a few
  // grey levels moves a patch match by well under the bar; a patch textured across one direction only (wood grain, a row of
  // book spines) cannot tell a shift along the stripes from none.
  double min_gradient = 4.0;
  // Dynamic.RigidMovers.growOverSurface: the mask may grow from the superpixels that follow a rigid mover over the
  // unmeasured superpixels of the same surface (no track, no long-baseline point, no occlusion edge between, each
  // step at most Dynamic.BaselineTracks.growDissimilarity apart), outside the dynamic clusters too: a door's plain
  // panel moves with its textured parts, and gives the samples nothing to vote on. The growth stays within the
  // movers' regions (superpixelsNearMovers), as their votes do: from a box's superpixels it would otherwise run on
  // over the plain, shadowed floor beside it.
  bool grow_over_surface = false;
  void check() const;
};

}  // namespace amos::dynamic
