#pragma once
// Initial pose of the current frame (paper Section III-D): three candidate models, each scored by its inliers
// (reprojection error below a threshold) over one common set of 3D-2D correspondences; the model with the most
// inliers gives the initial pose used by the dynamic judgement.
//   1. Reference keyframe: its keypoints (with their 3D world points) tracked into the current frame by LK,
//      then PnP RANSAC (the paper's EPnP; here AP3P minimal samples by default, see InitialPoseOptions::pnp).
//   2. Last frame: corners tracked from the last frame, lifted to 3D with the last depth and pose (Eq. 6),
//      then PnP RANSAC. Robust when the reference keyframe is old or the motion fast.
//   3. Constant velocity: the last inter-frame motion applied once more. Useful when PnP drifts.
// Everything here is a pure function of its inputs; the caller keeps the keyframe, last frame and velocity.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/geometry/pnp_ransac.h"

namespace amos::dynamic {

struct InitialPoseOptions {
  // Dynamic.InitialPose.inlierThreshold: a correspondence supports a pose when its reprojection error is below
  // sqrt(5.99) * 1 px = 2.45 px: the 95% chi-square bound for a 2-D error with ~1 px per-axis noise (LK track
  // noise plus the depth noise of the lifted point seen from a slightly moved camera).
  double inlier_threshold_px = 2.45;
  // PnP RANSAC for models 1 and 2 (its defaults; Dynamic.InitialPose.minimalSolver picks the minimal solver:
  // AP3P by default, the paper's EPnP for ablation; see geometry/pnp_ransac.h for why three points).
  geometry::PnpRansacOptions pnp;
  // Dynamic.InitialPose.keyframeMaxPoints: model 1 tracks at most this many of the reference keyframe's map-point
  // keypoints (every k-th, which keeps the extractor's spread over the image and the levels; 0 = all). The model
  // only seeds the tracker's pose, and EPnP RANSAC with a few hundred spread correspondences is as good as with a
  // thousand, while LK and the RANSAC's inlier counting cost grow with the number. Matters once the keyframes hold
  // many points (Dynamic.priorMaskedExtraction puts the whole feature budget on the static part of the view).
  int keyframe_max_points = 300;
  // Dynamic.InitialPose.selectByCoverage: of the hypotheses (inside the PnP RANSACs, PnpRansacOptions::
  // coverage_cols / rows) and of the three models whose inliers number at least half the most any of them has
  // (PnpRansacOptions::coverage_min_support), the one whose inliers cover the most of the image wins (cells of an
  // 8 x 6 grid holding at least one inlier; ties: more inliers). A mover is compact and the static world surrounds
  // it: when a textured person holds most of the corners and the detector has not found it, the motion that
  // follows the person has the most inliers, but in a few cells. The floor of half the most inliers keeps a pose
  // that follows some people of a crowd, with a few chance inliers in many cells, from winning. Measurements:
  // docs/experiments/front-end-defaults.md.
  bool select_by_coverage = true;
  void check() const;
};

// 3D world points and the undistorted current-frame pixels that observe them.
struct PoseCorrespondences {
  std::vector<Eigen::Vector3d> points_w;
  std::vector<Eigen::Vector2d> pixels;
  std::size_t size() const { return points_w.size(); }
  void append(const PoseCorrespondences& other);
};

enum class PoseModel { kReferenceKeyframe = 0, kLastFrame = 1, kConstantVelocity = 2 };
std::string toString(PoseModel model);

struct PoseCandidate {
  PoseModel model = PoseModel::kConstantVelocity;
  bool valid = false;  // false when the model could not produce a pose (too few correspondences, PnP failed)
  core::SE3 T_cw = core::SE3::Identity();
  int own_inliers = 0;     // PnP inliers over the model's own correspondences (0 for constant velocity)
  int common_inliers = 0;  // inliers over the common set (what the selection compares)
  int common_cells = 0;    // cells of the coverage grid holding one of them (select_by_coverage only)
};

struct InitialPoseResult {
  bool ok = false;  // at least one valid candidate
  core::SE3 T_cw = core::SE3::Identity();
  PoseModel model = PoseModel::kConstantVelocity;
  std::vector<PoseCandidate> candidates;  // in model order, for diagnostics
  int common_size = 0;
};

// At most max_count of `items`, every k-th (k = ceil(size / max_count)), in their order; max_count 0 = all. Model 1
// thins the reference keyframe's points this way (InitialPoseOptions::keyframe_max_points): the extractor's order
// runs through the levels and over the image, so every k-th keeps the spread.
std::vector<std::size_t> everyKth(const std::vector<std::size_t>& items, int max_count);

// Model 1 correspondences: reference keyframe keypoints (raw pixels) with their world points, tracked by LK from
// the keyframe image into the current image; returns the world points with the undistorted current pixels.
PoseCorrespondences keyframeCorrespondences(const FramePairPyramids& keyframe_to_current,
                                            const std::vector<cv::Point2f>& keyframe_pixels,
                                            const std::vector<Eigen::Vector3d>& keyframe_points_w,
                                            const core::PinholeCamera& camera, const CornerTrackingOptions& tracking);

// The tracks that do not start inside last_mask (CV_8U, != 0 = dynamic; empty: all of them), in their order. Model 2
// is fitted on these when Dynamic.Temporal.excludeFromFits is on: the corners on the last frame's movers do not
// vote for the camera's motion (in a crowd they are most of the tracks, and a pose that follows some of the people
// can gather as many inliers as the one that the static rest supports).
std::vector<PointTrack> tracksOffMask(const std::vector<PointTrack>& tracks, const cv::Mat& last_mask);

// Model 2 correspondences: last->current tracks with their world points from backProjectTracks (Eq. 6).
PoseCorrespondences lastFrameCorrespondences(const std::vector<PointTrack>& tracks,
                                             const std::vector<std::optional<Eigen::Vector3d>>& points_w,
                                             const core::PinholeCamera& camera);

// Model 3: velocity = T_cw_last * T_cw_before_last^-1 (the motion from the before-last camera to the last one,
// left-multiplied like every T_cw update); prediction = velocity * T_cw_last.
core::SE3 velocityFrom(const core::SE3& T_cw_last, const core::SE3& T_cw_before_last);
core::SE3 constantVelocityPose(const core::SE3& T_cw_last, const core::SE3& velocity);

// Correspondences whose reprojection error under T_cw is below threshold_px (points behind the camera never).
int countInliers(const core::SE3& T_cw, const PoseCorrespondences& correspondences, const core::PinholeCamera& camera,
                 double threshold_px);
// The same inliers' coverage: how many cells of a cols x rows grid over the camera's image hold at least one.
int countInlierCells(const core::SE3& T_cw, const PoseCorrespondences& correspondences,
                     const core::PinholeCamera& camera, double threshold_px, int cols, int rows);

// PnP RANSAC on one model's correspondences.
PoseCandidate poseFromCorrespondences(PoseModel model, const PoseCorrespondences& correspondences,
                                      const core::PinholeCamera& camera, const InitialPoseOptions& options);

// Scores every valid candidate on the common set and picks the one with the most inliers (ties: model order).
InitialPoseResult selectInitialPose(std::vector<PoseCandidate> candidates, const PoseCorrespondences& common,
                                    const core::PinholeCamera& camera, const InitialPoseOptions& options);

// All three models: keyframe and last-frame correspondences (either may be empty), the constant-velocity
// prediction when a velocity is known; the common set is the union of both correspondence sets.
InitialPoseResult estimateInitialPose(const PoseCorrespondences& keyframe, const PoseCorrespondences& last_frame,
                                      const core::SE3& T_cw_last, const std::optional<core::SE3>& velocity,
                                      const core::PinholeCamera& camera, const InitialPoseOptions& options);

}  // namespace amos::dynamic
