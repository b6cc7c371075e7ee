#pragma once
// Why the geometric stage misses a mover (issue 16): given one frame's front-end output and the ground-truth
// instance mask of that frame (synthetic sequences), what each moving instance got from every stage: tracks ending
// on it and their errors, the clusters it falls into (how much of each is the mover, their scores, the decisions)
// and how much of it the final mask covers. A tool for diagnosis, not part of the per-frame pipeline.
#include <opencv2/core.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "amos/dynamic/front_end_types.h"

namespace amos::dynamic {

struct MoverClusterView {
  int cluster = -1;
  int overlap_px = 0;         // mover pixels in the cluster
  int cluster_px = 0;         // the cluster's pixels
  int tracks = 0;             // tracks of the cluster that scored (ClusterScore::points)
  double initial_px = 0;      // Eq. 5 equivalent error under the initial pose
  double confirm_px = 0;      // ... under the refitted pose (0 without a refit)
  bool candidate = false, confirmed = false, dynamic = false;
};

struct MoverFrameDiagnosis {
  std::uint16_t id = 0;
  int pixels = 0;            // the mover's pixels in the frame
  int marked = 0;            // of which in the final mask
  int tracks = 0;            // tracks whose current pixel lies on the mover
  int tracks_scored = 0;     // of which with a reprojection error (a depth or an interval)
  double median_initial_px = 0, median_judged_px = 0;  // their errors under the initial / judged pose (0 if none)
  int epipolar_violators = 0;                          // of them beyond Dynamic.Epipolar.threshold
  int baseline_points = 0;         // points on the mover followed into the baseline frame (baseline_tracks.h)
  int baseline_moving = 0;         // of which beyond the bar
  double median_baseline_px = 0;   // their median residual over the baseline (0 if none)
  std::vector<MoverClusterView> clusters;              // by overlap, largest first
  // The first stage that lost the mover: "found" (>= half marked), "no-tracks", "mixed-cluster" (its main cluster
  // is mostly static surface), "below-threshold" (its clusters neither candidate nor confirmed), "no-decision"
  // (candidates without enough violators), "mask" (a dynamic cluster, but the per-superpixel mask left it out).
  std::string cause;
};

// out: DynamicFrontEnd::process's output for the frame; instances: CV_16U ids (0 = static); moving[id]: whether
// that instance moves in the frame. Instances at rest are not diagnosed.
std::vector<MoverFrameDiagnosis> diagnoseMovers(const FrontEndResult& out, const cv::Mat& instances,
                                                const std::vector<bool>& moving, const DynamicOptions& options);

}  // namespace amos::dynamic
