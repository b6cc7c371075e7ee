#pragma once
// The paper's two-stage anti-dynamics front end (Section III), frame in, mask out:
//   stage 1, potential motion regions: prior regions from instance segmentation (given as a mask) and
//     geometric clusters (depth-SLIC superpixels grouped by k-means) whose Cauchy-robust mean reprojection
//     error under the initial pose is high (Eq. 5-6);
//   stage 2, dynamic judgement: a fundamental matrix from last->current corner tracks (Eq. 7-8); a candidate
//     region holding epipolar violators (after boundary reassignment) is dynamic. So is a cluster whose error
//     stays high under the pose refitted on the tracks outside the candidates (reprojection_scoring.h: the
//     epipolar test is blind to motion along the epipolar lines, the depth-based error is not).
//   mask: per superpixel in and around the dynamic clusters (boundary_assignment.h), so that it follows the
//     mover's outline rather than the clusters' blobs.
//
// process() runs the stages in the paper's order; each is a function in its own file that takes the earlier stages'
// results, returns a small struct and fills its own part of DynamicDiagnostics:
//
//   prior = findPriorRegions(prior_mask);                      // frame_regions.h, III-A (each region is dynamic
//                                                              //   unless Dynamic.judgePriorRegions)
//   partition = computeGeometricPartition(bgr, depth);         // geometric_clustering.h, III-B (or given)
//   regions = findDecisionRegions(partition);                  // frame_regions.h, III-C (border blocks out)
//   tracks = trackCorners(last_gray, gray);                    // corner_tracking.h (or given)
//   candidates = scoreCandidates(tracks, regions, prior);      // candidate_scoring.h, III-C Eq. 5-6
//   confirmation = confirmUnderRefittedPose(candidates);       // pose_confirmation.h, III-C Eq. 5
//   epipolar = fitEpipolarEvidence(confirmation.fit_tracks);   // epipolar_evidence.h, III-C Eq. 7-8
//   depth = superpixelDepthEvidence(depth, last_depth);       // depth_evidence.h (Dynamic.Depth.enabled)
//   baseline = baselineMotion(tracks, baseline_gray);          // baseline_tracks.h, Eq. 6 over ten frames
//                                                              //   (Dynamic.BaselineTracks.enabled)
//   voting = voteClusters(epipolar.violators, candidates, confirmation);  // cluster_voting.h, III-C
//                                                              //   (+ the depth's and the baseline's clusters)
//   mask |= buildDynamicMask(candidates, confirmation, epipolar, voting); // mask_building.h, III-C boundaries
//   mask |= holdMotion(mask, last_hold_score);                 // motion_hold.h (Dynamic.Temporal.holdFrames)
//
// State: none. The caller keeps the last frame (gray, depth, pose) and the baseline frame (baseline_history.h) and
// passes them in with the current frame, so one DynamicFrontEnd can be shared, tested and benchmarked frame pair by
// frame pair. process() is const and thread-compatible (no mutable members).
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/baseline_tracks.h"
#include "amos/dynamic/depth_evidence.h"
#include "amos/dynamic/dynamic_options.h"

namespace amos::dynamic {

struct FrontEndInput {
  cv::Mat gray;        // current frame, CV_8UC1
  cv::Mat bgr;         // current frame, CV_8UC3 (superpixel colour)
  cv::Mat depth;       // current frame, CV_32F metres, 0 = invalid (superpixel depth)
  cv::Mat last_gray;   // last frame, CV_8UC1; empty on the first frame (then only the prior mask is used)
  cv::Mat last_depth;  // last frame, CV_32F metres (Eq. 6)
  core::SE3 T_cw_last = core::SE3::Identity();     // last frame's estimated pose
  core::SE3 T_cw_initial = core::SE3::Identity();  // current frame's initial pose (III-D)
  cv::Mat prior_mask;  // CV_8U, != 0 on prior dynamic objects (already dilated); empty = none
  // The last frame's final dynamic mask (CV_8U, 255 = dynamic), in the last frame's pixels; empty when unknown
  // (first frame, after a lost frame, mode none). Temporal evidence: movers rarely stop between two frames.
  cv::Mat last_mask;
  // The last frame's hold scores (FrontEndResult::hold_score, with Dynamic.Temporal.holdFrames); empty when
  // unknown.
  cv::Mat last_hold_score;
  // The depth and pose of the frame Dynamic.Depth.baselineFrames back (depth_evidence.h), for slow movers; empty
  // when unknown (the depth evidence then compares with the last frame only).
  cv::Mat baseline_depth;
  // That frame's grey image (CV_8UC1), for the long-baseline tracks (baseline_tracks.h); empty when unknown.
  cv::Mat baseline_gray;
  // Optional: the LK pyramids of this frame and of that one (buildPyramid with Dynamic.LK.*), built beforehand; when
  // either is empty the long-baseline tracks build them from gray and baseline_gray.
  ImagePyramid pyramid, baseline_pyramid;
  core::SE3 T_cw_baseline = core::SE3::Identity();
  // Optional: last->current corner tracks already computed (e.g. for the initial pose model 2); when null the
  // front end detects and tracks corners itself. Non-owning.
  const std::vector<PointTrack>* tracks = nullptr;
  // Optional: this frame's superpixels and clusters, computed ahead (they depend only on bgr and depth, with the
  // front end's options); when null the front end computes them. Non-owning.
  const GeometricPartition* partition = nullptr;
};

struct DynamicDiagnostics {
  bool geometry_ran = false;
  int superpixels = 0;
  int clusters = 0;
  int candidate_clusters = 0;  // potential motion regions: above threshold under the initial or the refitted pose
  int dynamic_clusters = 0;
  int confirmed_clusters = 0;  // of which above Dynamic.Reprojection.confirmThreshold under the refitted pose
  bool pose_refit_ok = false;
  int pose_refit_points = 0, pose_refit_inliers = 0;
  double pose_refit_sigma_px = 0;  // the static tracks' noise scale the refit found
  double confirm_threshold_px = 0;  // the confirmation threshold that followed from it
  int dynamic_superpixels = 0;  // superpixels in the mask (per-superpixel mask only)
  int tracks = 0;             // last->current corner tracks
  int tracks_with_depth = 0;  // of which lifted to 3D (Eq. 6) and reprojected
  int dynamic_points = 0;     // tracks beyond the epipolar threshold
  bool fundamental_ok = false;
  int f_fit_points = 0;           // tracks the fit used (those outside candidate and prior regions, or all)
  int f_ransac_inliers = 0;       // first (RANSAC) fit
  int f_refit_points = 0;         // points kept for the second fit
  int f_final_inliers = 0;        // inliers of the final F
  int depth_moving_superpixels = 0;  // superpixels whose depth moved (depth_evidence.h; 0 when it is off)
  int depth_dynamic_clusters = 0;    // clusters made dynamic by the depth evidence alone
  int baseline_points = 0;              // points followed into the baseline frame (baseline_tracks.h; 0 when off)
  int baseline_moving_points = 0;       // of which moving
  int baseline_dense_points = 0;        // of those, followed where points moved (densifyBaselineMotion)
  int baseline_dynamic_clusters = 0;    // clusters made dynamic by the long-baseline tracks alone
  int rigid_movers = 0;                 // rigid motions found among the moving points (rigid_movers.h; 0 when off)
  int rigid_superpixels = 0;            // superpixels whose samples follow one of them
  int held_superpixels = 0;       // superpixels dynamic by the temporal hold alone (motion_hold.h; 0 when off)
  int prior_regions = 0;          // connected components of the prior mask
  int dynamic_prior_regions = 0;  // of which kept in the mask
};

struct FrontEndResult {
  cv::Mat mask;  // CV_8U, 255 = dynamic (features there must not be used), 0 = static; image size
  DynamicDiagnostics diagnostics;
  cv::Mat hold_score;  // CV_8U, the temporal hold's scores (motion_hold.h: per sample) for the next frame; empty: off
  std::vector<std::pair<std::string, double>> timings_ms;  // stage name -> wall time, in execution order
  // Geometric detail for visualisation and tests (empty when the geometric stage did not run):
  cv::Mat superpixel_labels;                                 // CV_32S depth-SLIC superpixel of every pixel
  cv::Mat cluster_map;                                       // CV_32S geometric cluster of every pixel
  std::vector<ClusterScore> cluster_scores;                  // Eq. 5 per cluster, initial pose
  std::vector<ClusterScore> confirm_scores;                  // Eq. 5 per cluster, refitted pose (empty without)
  core::SE3 T_cw_judged = core::SE3::Identity();             // the refitted pose, else the initial one
  std::vector<bool> dynamic_cluster;                         // per cluster
  std::vector<PointTrack> tracks;                            // the tracks used
  std::vector<std::optional<double>> reprojection_error_px;  // per track (Eq. 5's ||e||), empty without depth
  std::vector<std::optional<double>> judged_error_px;        // per track under T_cw_judged (points, else intervals)
  std::vector<double> epipolar_distance_px;                  // per track (infinity when there was no F)
  std::vector<BaselinePoint> baseline_points;                // followed into the baseline frame (baseline_tracks.h)
  double baseline_bar_px = 0;                                // what their residual had to exceed
};

class DynamicFrontEnd {
 public:
  DynamicFrontEnd(const core::PinholeCamera& camera, const DynamicOptions& options);

  FrontEndResult process(const FrontEndInput& input) const;

  const DynamicOptions& options() const { return options_; }

  // The per-track border rule's band (Dynamic.Boundary.borderBlocks off): half an LK window and a pixel, the width
  // within which a track's finest-level window is cut by the image frame.
  int edgeBand() const { return options_.tracking.lk_window / 2 + 1; }

 private:
  core::PinholeCamera camera_;
  DynamicOptions options_;
  DepthSampleGrid depth_grid_;  // with Dynamic.Depth.enabled
  DepthSampleGrid hold_grid_;   // with Dynamic.Temporal.holdFrames
};

}  // namespace amos::dynamic
