#pragma once
// Temporal hold of the geometric dynamic mask (issue 16: movers that slow down before they stop).
//
// A mover that eases into a stop (a door swinging into its end stop, a pushed chair rolling out) keeps moving for a
// while below what any test can see: over the long baseline's ten frames a slow end moves a door's leaf by less
// than the 2 px bar (at 2.5 m and f = 525 px that is 3 cm/s), and within one frame by a tenth of that. The paper's
// tests judge each frame on its own, so such a mover drops out of the mask while it still moves and its points,
// mapped or matched then, drift with it. The hold carries the evidence of the frames before, for as long as it was
// seen: a surface found moving in n frames stays dynamic for the n - 1 frames after it was last found (at most H),
// then it rejoins the static world (a mover that stopped is mapped again, not masked for ever). A surface found in
// one frame only is not carried (a static surface's false positive usually is one), and a flicker of a few frames
// is carried for as few.
//
// How (per frame, after the mask of this frame's own evidence is built), on a grid of samples (every 4th pixel):
//   - each sample with a depth is lifted, moved into the last frame by the judged pose and the last pose, and takes
//     the score of the last frame's sample there when the last frame saw the same surface (its depth there within
//     3 sqrt(2) sigma(z) of the predicted one, sigma the sensor's noise model, and at least 1 cm: a surface that a
//     mover uncovered, or a mover that left its place, does not inherit the score of what stood there); else its
//     score was 0;
//   - found moving in this frame (in the evidence mask): score + 1, at most H + m - 1; otherwise score - 1, at least
//     0 (m = 2 unless min_frames says otherwise);
//   - a superpixel not found moving, most of whose samples keep a score of at least max(1, m - 1), is held: added to
//     the mask; unless this frame shows it static (its tracks or its points followed over the long baseline moved
//     with the static world, within the noise): the hold
//     carries evidence of motion, and wrong evidence too (a frame judged against a pose that followed a mover marks
//     the static world), which static evidence ends.
// Scores live on the samples, carried point by point, so the held region does not spread from frame to frame as
// the superpixels change; the mask keeps to the outline the current superpixels give.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/depth_evidence.h"

namespace amos::dynamic {

struct MotionHoldInput {
  const cv::Mat* evidence_mask = nullptr;  // CV_8U, != 0 where this frame's own tests found motion
  const cv::Mat* labels = nullptr;         // CV_32S superpixel labels of the current frame, 0..count-1
  int count = 0;
  const cv::Mat* depth = nullptr;          // current frame, CV_32F metres, 0 = invalid
  core::SE3 T_cw = core::SE3::Identity();  // current frame's judged pose
  // The last frame's hold scores (MotionHold::score: CV_8U, one per sample of the same grid) and depth (CV_32F
  // metres, image size); both empty when there was no last frame.
  const cv::Mat* last_score = nullptr;
  const cv::Mat* last_depth = nullptr;
  core::SE3 T_cw_last = core::SE3::Identity();
  // Optional, per superpixel: positive evidence that it is static in this frame (stillSuperpixels: its tracks
  // moved with the static world within the noise; baselineStaticSuperpixels: its points stayed put over the long
  // baseline). Such a superpixel is not held, and its samples' scores drop to 0.
  const std::vector<bool>* seen_static = nullptr;
};

struct MotionHold {
  cv::Mat score;             // CV_8U per grid sample (grid rows x columns), for the next frame (last_score)
  std::vector<bool> held;    // per superpixel: dynamic by the hold alone
  int held_superpixels = 0;
};

// Per superpixel (labels CV_32S, count labels): whether at least two tracks end on it with an error under the judged
// pose (judged_error_px, per track; nullopt: none) whose median is within 2 sigma_px, the static tracks' noise scale
// (robust_scale.h: a static point's residual length has its median at 1.18 sigma): positive evidence, at the noise
// level of this frame, that it is static (MotionHoldInput::seen_static).
std::vector<bool> stillSuperpixels(const std::vector<PointTrack>& tracks,
                                   const std::vector<std::optional<double>>& judged_error_px, const cv::Mat& labels,
                                   int count, double sigma_px);

// noise: the sensor's axial noise model (DepthEvidenceOptions::sigma). hold_frames (H) >= 1; min_frames (m) >= 2:
// only a surface found moving in at least m frames is held, for the n - m + 1 frames after the last of n (at most H;
// H + m <= 256: the score, up to H + m - 1, is 8-bit). grid: the sample grid (DepthSampleGrid with the camera's
// size), the same from frame to frame.
MotionHold holdMotion(const MotionHoldInput& in, const core::PinholeCamera& camera, const DepthSampleGrid& grid,
                      const DepthEvidenceOptions& noise, int hold_frames, int min_frames = 2);

}  // namespace amos::dynamic
