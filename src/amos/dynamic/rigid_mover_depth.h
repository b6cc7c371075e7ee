#pragma once
// Depth votes for the rigid movers (issue 16, Dynamic.RigidMovers.depthVotes). rigid_movers.h asks every textured
// sample which motion its 3x3 patch follows over the long baseline; a door's plain panel has no texture to ask, and
// the depth evidence (depth_evidence.h) cannot use a surface that recedes over ten frames, because from the current
// frame a receding surface looks like background that a mover has uncovered (the static world's point lies behind
// what the baseline frame saw there: hidden, not refuted).
//
// Asked the other way round it is not ambiguous. Each sample of the baseline frame's depth is lifted and moved into
// the current camera by each hypothesis, the static world's motion and a mover's (the paper's Eq. 6 with the depth
// as the residual, as in depth_evidence.h, with two hypotheses as in rigid_movers.h). A hypothesis is refuted only
// when the current frame sees through the point it predicts (its depth there is farther by more than the noise:
// free space, which no occluder explains), and supported when the current depth there matches. A sample votes for
// the mover where the mover's motion is supported and the static world's refuted, and the vote goes to the current
// superpixel where the mover's motion puts it: a door that swung away from the camera was nearer ten frames ago,
// the current frame sees past where its points were, and they are found again, farther, where the door now is.
// Background that the door uncovered was hidden from the baseline frame and has no sample there; the floor ahead
// of a box was seen by the baseline and is now hidden by the box, which refutes nothing. A sample votes for the
// static world where it is supported and the mover refuted (the wall beside a door's leaf).
//
// The bars are the depth evidence's: support within max(violationSigmas sqrt(2) sigma(z), minResidual,
// minRelativeResidual z) (two measurements of the sensor's noise, and its bias within one frame's comparison);
// refutation beyond max(violationSigmas sqrt(2) sigma(z), minResidual, baselineRelativeResidual z) (the bias a
// real sensor shows over ten frames, TUM fr2/desk).
#include <opencv2/core.hpp>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/depth_evidence.h"
#include "amos/dynamic/rigid_movers.h"

namespace amos::dynamic {

// The depth votes of the baseline frame's samples (grid; baseline_depth CV_32F metres) between the static world
// (T_bc_static: current camera -> baseline camera) and each mover, counted on the current frame's superpixels
// (labels CV_32S, count labels; depth CV_32F). A sample speaks about a mover only where that vote is counted within
// reach_px of the mover's region (the reach of its intensity votes). Samples on a depth edge (depth_edge_ratio) in
// either frame or beyond depth_options.max_depth_m do not vote.
std::vector<RigidSampleVote> rigidMoverDepthVotes(const std::vector<RigidMover>& movers, const core::SE3& T_bc_static,
                                                  const cv::Mat& depth, const cv::Mat& baseline_depth,
                                                  const core::PinholeCamera& camera, const DepthSampleGrid& grid,
                                                  const cv::Mat& labels, int count, int reach_px,
                                                  double depth_edge_ratio, const DepthEvidenceOptions& depth_options);

}  // namespace amos::dynamic
