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
// Per superpixel: moving when at least minVotes of its points move and they outnumber its static ones, the points
// counted over the superpixel and its neighbours on the same surface (Dynamic.BaselineTracks.poolNeighbours); per
// decision cluster: dynamic when at least minVotes of its points move and they make up clusterShare of them. A moving
// superpixel seeds the mask even where the one-frame votes call it static (mask_building.h): over ten frames its
// motion is measured, over one it is within the noise.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/boundary_assignment.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/reprojection_scoring.h"

namespace amos::dynamic {

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
  // Dynamic.BaselineTracks.poolNeighbours: a superpixel's vote also counts the points of its neighbours across
  // borders that are not occlusion edges (the superpixel graph, boundary_assignment.h), and a superpixel whose own
  // points are mostly static never moves. The points that survive ten frames are sparse: on a door leaf ~1 per
  // superpixel (objects_xyz, diagnose-movers: 26-36 moving points on a 40000 px door that spans ~40 superpixels),
  // so two votes on one superpixel are rare even where every point of the surface moves. Off by default: it is a
  // trade, not a gain (session 17, README "Movers no detector knows"): door recall 0.44 -> 0.56 on objects_xyz
  // seeds 5-7, but the floor beside a pushed box pools the box's points (box_push seed 4 precision 0.83 -> 0.79)
  // and walking_rpy seed 4 / walking_static seed 3 go from 1.41x / 1.49x to 1.96x / 1.59x their static twins.
  bool pool_neighbours = false;
  // Dynamic.BaselineTracks.pooledVotes: moving points such a pooled count needs (and more than its static ones):
  // one more than minVotes, as it draws on ~6 superpixels instead of one (on the first 50 frames of TUM fr2/desk,
  // static, 2 gave 3.2 % of the pixels marked against 2.6 % without pooling, 3 gave 2.8 %).
  int pooled_votes = 3;
  // Dynamic.BaselineTracks.densifyPoints: where a point moved, more points are followed: in the superpixel of every
  // moving point and in its neighbours on the same surface (no occlusion edge between them), up to this many each,
  // the best textured first (densifyBaselineMotion). The corners are ~1 per superpixel on a door leaf, too sparse
  // for two votes; pooling the neighbours' votes instead (poolNeighbours) lent a mover's points to the static floor
  // beside it, whereas a measured floor superpixel votes with its own points. 0 = off.
  int densify_points = 0;
  // Dynamic.BaselineTracks.densifyGrid: candidate pixels lie on a grid of this step [px].
  int densify_grid_px = 4;
  // Dynamic.BaselineTracks.densifyMinGradient: a candidate needs at least this RMS intensity gradient [grey levels
  // per px] in its weakest direction over 7x7 px (Shi-Tomasi's smaller eigenvalue, square-rooted): at 4 the image
  // noise of a few grey levels moves LK by well under the 2 px bar over an 11x11 window; flat or edge-only patches
  // (the aperture problem) are left out.
  double densify_min_gradient = 4.0;
  // Dynamic.BaselineTracks.growOverSurface: the mask may grow from a superpixel the long-baseline points move over
  // the superpixels of the same surface that nothing measured (no track vote, no long-baseline point), through
  // borders that are not occlusion edges and between superpixels at most growDissimilarity apart, even outside
  // the dynamic clusters (mask_building.h). The plain panel of a door gives no point to follow and shares its
  // decision clusters with the wall it swings in front of, so only its sign and edges were marked.
  bool grow_over_surface = false;
  // Dynamic.BaselineTracks.growDissimilarity: Eq. 1 without the position term (superpixelDissimilarity); 1 = a colour
  // difference of colourScale Lab units, or a depth step of depthScale (10 cm), the unit of SLIC's own distance.
  double grow_dissimilarity = 1.0;
  void check() const;
};

struct BaselinePoint {
  cv::Point2f current;    // raw pixel in the current frame
  cv::Point2f found;      // raw pixel where LK found it in the baseline frame
  double residual_px = 0;  // |found - prediction - common shift| (undistorted pixels)
  bool moving = false;
  // Added by densifyBaselineMotion: chosen where motion was already found, so not a fair sample of a cluster (they
  // vote per superpixel, not in baselineMovingClusters' share).
  bool densified = false;
};

struct BaselineMotion {
  std::vector<BaselinePoint> points;  // those with a trusted depth that LK followed both ways
  bool ok = false;                    // enough points (Dynamic.Reprojection.refitMinPoints) to judge any
  Eigen::Vector2d shift_px = Eigen::Vector2d::Zero();  // the median residual, removed from every point
  double sigma_px = 0;                // the points' noise scale around it
  double bar_px = 0;                  // max(min_motion_px, sigmas * sigma_px)
  int moving_points = 0;
};

// Steps 1-4 above for `points` (raw current-frame pixels; the current frame's tracked corners). gray/depth/T_cw:
// current frame (CV_8UC1, CV_32F metres, the judged pose); baseline_gray / T_cw_baseline: the baseline frame.
// lk: window, levels, stop criteria and forward-backward threshold of LK; reprojection: depth trust rules and the
// number of points needed (refitMinPoints).
BaselineMotion baselineMotion(const std::vector<cv::Point2f>& points, const cv::Mat& gray, const cv::Mat& depth,
                              const core::SE3& T_cw, const cv::Mat& baseline_gray, const core::SE3& T_cw_baseline,
                              const core::PinholeCamera& camera, const CornerTrackingOptions& lk,
                              const ReprojectionOptions& reprojection, const BaselineTrackOptions& options);
// The same on the two frames' LK pyramids built beforehand (buildPyramid with lk: the same result), which a pipeline
// has anyway.
BaselineMotion baselineMotion(const std::vector<cv::Point2f>& points, const ImagePyramid& pyramid,
                              const cv::Mat& depth, const core::SE3& T_cw, const ImagePyramid& baseline_pyramid,
                              const core::SE3& T_cw_baseline, const core::PinholeCamera& camera,
                              const CornerTrackingOptions& lk, const ReprojectionOptions& reprojection,
                              const BaselineTrackOptions& options);

// Where `motion` found moving points, more points: in each superpixel (labels: CV_32S, count labels) holding a moving
// point and its neighbours across non-occlusion borders (graph; null: the superpixel alone), up to
// options.densify_points grid pixels of enough texture, apart from the points there by LK's window radius; followed
// into the baseline frame as in baselineMotion and judged against its shift and bar (not re-estimated: the first
// points are spread over the image, these are not). With baseline_depth (CV_32F metres; empty: no check) only points
// the baseline frame saw are followed: its depth where the point is predicted is not nearer by more than max(2 cm,
// 4 %) (a walker stood in front of the floor he has since uncovered; LK would follow him and call the floor moving).
// Appended to motion.points; returns how many were followed.
int densifyBaselineMotion(BaselineMotion& motion, const ImagePyramid& pyramid, const cv::Mat& depth,
                          const core::SE3& T_cw, const ImagePyramid& baseline_pyramid, const cv::Mat& baseline_depth,
                          const core::SE3& T_cw_baseline, const core::PinholeCamera& camera, const cv::Mat& labels,
                          int count, const SuperpixelGraph* graph, const CornerTrackingOptions& lk,
                          const ReprojectionOptions& reprojection, const BaselineTrackOptions& options);

// The structure tensor of the 7x7 window around (u, v) of a CV_8UC1 image: the mean products of the intensity
// gradient's components (grey levels^2 per px^2); its quadratic form in a unit direction is the mean squared
// gradient along it, i.e. how well the window tells a shift along that direction from none. (u, v) must lie at
// least 4 px inside the image.
struct WindowStructure {
  double xx = 0, xy = 0, yy = 0;
  double along(double dx, double dy) const { return dx * dx * xx + 2 * dx * dy * xy + dy * dy * yy; }
};
WindowStructure windowStructure(const cv::Mat& gray, int u, int v);

// Its smaller eigenvalue: the weakest direction's mean squared gradient, what LK's precision there depends on (Shi
// and Tomasi's "good features to track").
double windowTexture(const cv::Mat& gray, int u, int v);

// Per superpixel (labels: CV_32S, count labels): whether at least options.min_votes of its points move and they
// outnumber its static ones, counting the densified points or not (a superpixel is moving either way: they add
// evidence of motion, they do not outvote the corners). With options.pool_neighbours and a graph of these
// superpixels, the points of its neighbours across non-occlusion borders count too, unless its own points are
// mostly static.
std::vector<bool> baselineMovingSuperpixels(const BaselineMotion& motion, const cv::Mat& labels, int count,
                                            const BaselineTrackOptions& options,
                                            const SuperpixelGraph* graph = nullptr);

// Per superpixel (labels: CV_32S, count labels): whether at least options.min_votes of its points (the corners'
// own, not densified ones) stayed where the static world puts them over the baseline and they outnumber its moving
// ones: positive evidence that it is static (the temporal hold releases such a superpixel, motion_hold.h).
std::vector<bool> baselineStaticSuperpixels(const BaselineMotion& motion, const cv::Mat& labels, int count,
                                            const BaselineTrackOptions& options);

// Per superpixel (labels: CV_32S, count labels): how many of motion's points lie on it.
std::vector<int> baselinePointsPerSuperpixel(const BaselineMotion& motion, const cv::Mat& labels, int count);

// Per cluster (decision_map: CV_32S, -1 = takes no part; num_clusters): whether at least options.min_votes of its
// points move and they are at least options.cluster_share of its points. Densified points do not count: the share
// is of the corners, spread over the cluster independently of where it moves.
std::vector<bool> baselineMovingClusters(const BaselineMotion& motion, const cv::Mat& decision_map, int num_clusters,
                                         const BaselineTrackOptions& options);

}  // namespace amos::dynamic
