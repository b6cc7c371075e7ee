#pragma once
// Rigid movers over the long baseline (issue 16): the long-baseline points that move (baseline_tracks.h) are
// sparse, about one per superpixel on a door leaf, and a slow mover's superpixels are each held by one or two of
// them, too few to outvote the one-frame tracks that move below their bar. But a door, a box or a chair moves as
// one rigid body: its moving points share one motion. That motion is fitted (EPnP RANSAC on the moving points:
// current-frame point lifted with its depth -> where LK found it in the baseline frame), and every textured sample
// of the current frame is then asked which motion explains it over the baseline: the static world's (fitted the
// same way on the points that stayed) or the mover's. That is the paper's reprojection test (Eq. 6) turned into a
// test between two hypotheses per pixel, with the baseline image as the measurement: a sample votes for the
// hypothesis under which its 3x3 patch matches the baseline image better by a margin above the images' noise, and
// only where the two hypotheses put it apart (near a door's hinge they do not, and the sample abstains). A
// superpixel moves when its samples vote for a mover and outnumber those for the static world two to one: a plain
// panel without texture gives no vote either way and is left to the region growing. A mover is a compact body: its
// points must outnumber the points that stayed within the box around them, and it speaks only for the samples near
// that box.
#include <opencv2/core.hpp>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/evidence/baseline_tracks.h"
#include "amos/evidence/evidence_frames.h"
#include "amos/dynamic/depth_slic.h"
#include "amos/dynamic/reprojection_scoring.h"
#include "amos/dynamic/evidence_options.h"

namespace amos::evidence {

using dynamic::BaselineMotion;
using dynamic::ReprojectionOptions;
using dynamic::RigidMoverOptions;
using dynamic::Superpixel;


struct RigidMover {
  core::SE3 T_bc;          // current camera -> baseline camera under this mover's motion
  int inliers = 0;         // moving points it explains
  double shift_px = 0;     // median distance of its inliers' predictions from the static world's
  cv::Rect2f region;       // the box around its inliers in the current frame (raw pixels)
};

// A sample's vote: for mover `mover` (>= 0), or for the static world against mover -1 - mover.
struct RigidSampleVote {
  int superpixel;
  int mover;
};


struct RigidMoverVerdict {
  core::SE3 T_bc_static = core::SE3::Identity();  // the static world's motion (refined on the points that stayed)
  std::vector<RigidMover> movers;
  std::vector<bool> moving;  // per superpixel
  int moving_superpixels = 0;
  int mover_votes = 0, static_votes = 0;  // samples that decided
};

// The current frame (judged pose) and the baseline frame, seen by one camera. The baseline's depth only tells which
// predictions it saw (one nearer by more than max(2 cm, 4 %) was hidden there) and may be empty.
struct RigidMoverFrames {
  const core::PinholeCamera& camera;
  PosedImages current;
  PosedImages baseline;
};

// The rigid motions among motion's moving points, and the superpixels whose samples follow one of them rather than
// the static world. reprojection: depth trust rules. Empty `moving` (all false) when no rigid motion has minInliers
// points.
RigidMoverVerdict rigidMoverSuperpixels(const BaselineMotion& motion, const RigidMoverFrames& frames,
                                        const SuperpixelLabels& superpixels, const ReprojectionOptions& reprojection,
                                        const RigidMoverOptions& options);

// Whether p lies within reach pixels of the box r (a mover's region and the samples it speaks for).
bool withinReach(const cv::Rect2f& r, const cv::Point2f& p, float reach);

// Per superpixel, whether its centroid lies within reach_px of one of the boxes.
std::vector<bool> superpixelsNearBoxes(const std::vector<Superpixel>& superpixels,
                                       const std::vector<cv::Rect2f>& boxes, int reach_px);

// Per superpixel, whether its centroid lies within reach_px of a mover's region (the box around its inliers):
// the samples a mover speaks for, and the surface its growth may cover.
std::vector<bool> superpixelsNearMovers(const std::vector<Superpixel>& superpixels,
                                        const std::vector<RigidMover>& movers, int reach_px);

}  // namespace amos::evidence
