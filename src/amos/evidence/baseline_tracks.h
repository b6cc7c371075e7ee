#pragma once
// Long-baseline tracks: the paper's reprojection test (Eq. 6: back-project with depth, reproject with the pose,
// compare with where the point was tracked) between the current frame and the frame Dynamic.Depth.baselineFrames
// back, for movers too slow for one frame (issue 16). A door swinging at 1 deg per frame moves its leaf by 0.5-2 px
// per frame at 3 m, inside the one-frame bar (max(1 px, 5 sigma)); over 10 frames it moves 5-20 px while a static
// point's error stays at LK's noise plus what the two poses' error does to all points alike, which is removed.
//
// Per current-frame point with a trusted depth (backProjectTracks' rules, and no depth edge in its whole LK window:
// at an occlusion edge the far side shifts by the parallax of the whole baseline, which LK reads as motion):
//   1. lift it with the current depth and pose, project it into the baseline frame: where the static world puts it;
//   2. LK from the current image into the baseline image, started at that prediction (so that a static point
//      converges at once and a mover is found up to LK's reach, ~40 px, from it), checked forward-backward;
//   3. the median of the residuals (found - prediction) is removed from each: the two tracked poses' relative error,
//      mostly rotation, shifts the image nearly uniformly (~1 px per 0.1 deg); sigma = the noise around it (from the
//      median length, as refitPose). Not a 6-DoF refit: where the scene is two planes (a door and its wall) a
//      translation and a rotation together explain a mover's sideways shift exactly, and a refit would absorb it;
//   4. a point moves when its residual exceeds max(minMotion, sigmas * sigma).
// Per superpixel: moving when at least minVotes of its points move and they outnumber its static ones; per decision
// cluster: dynamic when at least minVotes of its points move and they make up clusterShare of them. A moving
// superpixel seeds the mask even where the one-frame votes call it static (mask_building.h): over ten frames its
// motion is measured, over one it is within the noise.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/baseline_motion.h"
#include "amos/dynamic/boundary_assignment.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/dynamic/reprojection_scoring.h"
#include "amos/dynamic/evidence_options.h"

namespace amos::evidence {

using dynamic::BaselineMotion;
using dynamic::BaselinePoint;
using dynamic::BaselineTrackOptions;
using dynamic::CornerTrackingOptions;
using dynamic::ImagePyramid;
using dynamic::ReprojectionOptions;


// The current frame (gray CV_8UC1, depth CV_32F metres, the judged pose) and the baseline frame (gray, pose).
struct BaselineImages {
  const cv::Mat& gray;
  const cv::Mat& depth;
  const core::SE3& T_cw;
  const cv::Mat& baseline_gray;
  const core::SE3& T_cw_baseline;
};

// The same with the two frames' LK pyramids built beforehand (buildPyramid with Dynamic.LK.*: the same result),
// which a pipeline has anyway.
struct BaselinePyramids {
  const ImagePyramid& pyramid;
  const cv::Mat& depth;
  const core::SE3& T_cw;
  const ImagePyramid& baseline_pyramid;
  const core::SE3& T_cw_baseline;
};

// Steps 1-4 above for `points` (raw current-frame pixels; the current frame's tracked corners). options: tracking
// (LK's window, levels, stop criteria and forward-backward threshold), reprojection (depth trust rules and the
// number of points needed, refitMinPoints) and baseline_tracks.
BaselineMotion baselineMotion(const std::vector<cv::Point2f>& points, const BaselineImages& frames,
                              const core::PinholeCamera& camera, const dynamic::DynamicOptions& options);
BaselineMotion baselineMotion(const std::vector<cv::Point2f>& points, const BaselinePyramids& frames,
                              const core::PinholeCamera& camera, const dynamic::DynamicOptions& options);

// The structure tensor of the 7x7 window around (u, v) of a CV_8UC1 image: the mean products of the intensity
// gradient's components (grey levels^2 per px^2); its quadratic form in a unit direction is the mean squared
// gradient along it, i.e. how well the window tells a shift along that direction from none. (u, v) must lie at
// least 4 px inside the image.
struct WindowStructure {
  double xx = 0, xy = 0, yy = 0;
  double along(double dx, double dy) const { return dx * dx * xx + 2 * dx * dy * xy + dy * dy * yy; }
};
WindowStructure windowStructure(const cv::Mat& gray, int u, int v);

// Per superpixel (labels: CV_32S, count labels): whether at least options.min_votes of its points move and they
// outnumber its static ones.
std::vector<bool> baselineMovingSuperpixels(const BaselineMotion& motion, const cv::Mat& labels, int count,
                                            const BaselineTrackOptions& options);

// Per superpixel (labels: CV_32S, count labels): how many of motion's points lie on it.
std::vector<int> baselinePointsPerSuperpixel(const BaselineMotion& motion, const cv::Mat& labels, int count);

// Per cluster (decision_map: CV_32S, -1 = takes no part; num_clusters): whether at least options.min_votes of its
// points move and they are at least options.cluster_share of its points.
std::vector<bool> baselineMovingClusters(const BaselineMotion& motion, const cv::Mat& decision_map, int num_clusters,
                                         const BaselineTrackOptions& options);

}  // namespace amos::evidence
