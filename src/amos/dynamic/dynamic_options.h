#pragma once
// Options of the whole anti-dynamics front end (paper Section III), YAML section "Dynamic.". Every default is
// argued beside it in the struct that owns it, from sensor noise, image size and typical indoor motion, not
// fitted to any sequence.
#include <string>

#include "amos/dynamic/boundary_assignment.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/depth_slic.h"
#include "amos/dynamic/epipolar_check.h"
#include "amos/dynamic/evidence_options.h"
#include "amos/dynamic/geometric_clustering.h"
#include "amos/dynamic/initial_pose_models.h"
#include "amos/dynamic/prior_propagation.h"
#include "amos/dynamic/reprojection_scoring.h"

namespace amos::dynamic {

// Which stages produce the mask: none (plain SLAM), prior (segmentation only, III-A), geometry (superpixel
// clusters judged by reprojection + epipolar tests only, III-B/C), full (both, the paper's system).
enum class DynamicMode { kNone, kPrior, kGeometry, kFull };

// "none" | "prior" | "geometry" | "full"; throws core::Error naming Dynamic.mode otherwise.
DynamicMode parseDynamicMode(const std::string& text);
std::string toString(DynamicMode mode);

// Temporal evidence from the last frame's final dynamic mask (FrontEndInput::last_mask): a mover seen in the
// last frame is most likely still moving 33 ms later.
struct TemporalOptions {
  // Dynamic.Temporal.excludeFromFits: the tracks starting inside the last mask take no part in the last-frame model
  // of the initial pose (tracksOffMask, initial_pose_models.h), the pose refit and the fundamental-matrix fit (they
  // still take part in every decision). Keeps a mover that the detector and the candidate stage miss in this frame
  // from biasing the pose the movers are judged against.
  bool exclude_last_mask_from_fits = true;
};

struct DynamicOptions {
  DynamicMode mode = DynamicMode::kFull;  // Dynamic.mode
  // Every prior (segmented person) region is removed, as in paper III-A ("feature points that fall within the
  // region of highly dynamic objects will be removed").
  // Dynamic.priorMaskedExtraction: every keypoint in a (dilated) prior region is removed anyway, so ORB features may be detected outside those regions in the first place: the feature budget
  // (ORBextractor.nFeatures) then goes to the static part of the image instead of being spent on people and thrown
  // away. The mask is the previous frame's (people move a few pixels per frame, well inside the dilation).
  bool prior_masked_extraction = true;
  // Dynamic.priorMaskedExtractionCoverage: ... but only once the mask covers at least this fraction of the image,
  // i.e. once more than half of the budget would be thrown away. Below that the static part still gets at least
  // half of the features, enough to track, and the unmasked extraction keeps the per-frame cost (a masked one puts
  // the whole budget on the static part: more points to match, track and adjust). Before the map exists the mask
  // is used at any coverage: the frame alone must then supply Tracking.initMinDepthPoints static points.
  // Measurements: docs/experiments/front-end-defaults.md.
  double prior_masked_extraction_coverage = 0.5;
  DepthSlicOptions superpixel;       // Dynamic.Superpixel.*
  ClusteringOptions cluster;         // Dynamic.Cluster.*
  CornerTrackingOptions tracking;    // Dynamic.Corners.*, Dynamic.LK.*
  ReprojectionOptions reprojection;  // Dynamic.Reprojection.*
  EpipolarOptions epipolar;          // Dynamic.Epipolar.*
  BoundaryOptions boundary;          // Dynamic.Boundary.*
  TemporalOptions temporal;          // Dynamic.Temporal.*
  DepthEvidenceOptions depth;        // Dynamic.Depth.*: movers without tracks, from the depth images
  BaselineTrackOptions baseline_tracks;  // Dynamic.BaselineTracks.*: slow movers, over Dynamic.Depth.baselineFrames
  RigidMoverOptions rigid_movers;        // Dynamic.RigidMovers.*: their rigid motions, tested per sample
  InitialPoseOptions initial_pose;   // Dynamic.InitialPose.* (used by tracking, III-D)
  PriorScheduleOptions prior;        // Dynamic.Prior.*: how often the person segmentation runs
  void check() const;
};

}  // namespace amos::dynamic
