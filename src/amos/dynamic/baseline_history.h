#pragma once
// The frames the comparisons over a longer baseline need (issue 16: movers too slow for one frame): the depth
// evidence's comparison with the frame Dynamic.Depth.baselineFrames back (depth_evidence.h) and the long-baseline
// tracks (baseline_tracks.h). The caller adds every tracked frame with its pose and asks for the one that many frames
// before the next; a lost frame starts the history again.
#include <opencv2/core.hpp>
#include <cstddef>
#include <deque>

#include "amos/core/pose.h"
#include "amos/dynamic/corner_tracking.h"

namespace amos::dynamic {

// A kept frame: its depth (the depth evidence), its grey image and, when it was built anyway, its LK pyramid (the
// long-baseline tracks; both may be empty when those are off) and its pose. The images are shared, not copied.
struct BaselineFrame {
  cv::Mat depth;
  cv::Mat gray;
  ImagePyramid pyramid;
  core::SE3 T_cw = core::SE3::Identity();
};

class BaselineHistory {
 public:
  // Keeps nothing when frames is 0 or 1 (the last frame is compared anyway).
  explicit BaselineHistory(int frames = 0) : frames_(frames > 1 ? static_cast<std::size_t>(frames) : 0) {}
  // A frame processed with its pose (the oldest beyond `frames` is dropped).
  void add(BaselineFrame frame);
  // After a lost frame: its pose would poison the comparison, so the history starts again.
  void clear() { frames_back_.clear(); }
  // The frame `frames` back from the next one, once that many were added; else null.
  const BaselineFrame* baseline() const;

 private:
  std::size_t frames_;
  std::deque<BaselineFrame> frames_back_;  // oldest first
};

}  // namespace amos::dynamic
