#pragma once
// What the front end's stages exchange with its caller: a frame pair in (FrontEndInput), the mask and what was found
// out (FrontEndResult, DynamicDiagnostics). Stage headers include this one, not dynamic_front_end.h.
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/baseline_motion.h"
#include "amos/dynamic/evidence_options.h"
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
  int baseline_dynamic_clusters = 0;    // clusters made dynamic by the long-baseline tracks alone
  int rigid_movers = 0;                 // rigid motions found among the moving points (rigid_movers.h; 0 when off)
  int rigid_superpixels = 0;            // superpixels whose samples follow one of them
  int prior_regions = 0;          // connected components of the prior mask
  int dynamic_prior_regions = 0;  // of which kept in the mask (all of them)
};

struct FrontEndResult {
  cv::Mat mask;  // CV_8U, 255 = dynamic (features there must not be used), 0 = static; image size
  DynamicDiagnostics diagnostics;
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

}  // namespace amos::dynamic
