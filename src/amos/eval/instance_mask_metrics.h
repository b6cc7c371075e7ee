#pragma once
// Per-mover accuracy of a dynamic mask (issue 16: recall and precision per mover type, and per phase of a mover
// that starts or stops moving). The ground truth is the synthetic instance mask (CV_16U ids, 0 = static scene) and,
// per frame, which instances move.
//   recall of an instance: share of its pixels marked dynamic over the frames where it moves;
//   precision of an instance: its marked pixels over its marked pixels plus the false positives attributed to it.
//     A false-positive pixel is attributed through the connected component (8-connectivity) of the predicted mask
//     it lies in: to the moving instance that component overlaps most. A component that overlaps no moving instance
//     is attributed to none (it still counts in the pooled precision of mask_metrics.h), so the per-instance
//     precision says how far the mask spills over a mover's outline, not how often the static world is marked.
//   at rest (frames where it does not move): the share of its pixels still marked, and after each stop the number
//     of frames until that share falls below kReleasedFraction (the object has rejoined the static scene: its
//     features are used and mapped again).
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace amos::eval {

// One instance in one frame.
struct InstanceFrameCounts {
  std::uint16_t id = 0;
  bool moving = false;
  std::int64_t pixels = 0;         // its pixels in the frame
  std::int64_t marked = 0;         // of which predicted dynamic
  std::int64_t attributed_fp = 0;  // static-scene pixels predicted dynamic in components it overlaps most (moving only)
};

// predicted: CV_8U, != 0 = dynamic; instances: CV_16U ids of the same size; moving[id] (ids beyond the vector's size
// are at rest). Returns the instances that are in the frame, ordered by id. Throws core::Error on bad input.
std::vector<InstanceFrameCounts> compareInstanceMasks(const cv::Mat& predicted, const cv::Mat& instances,
                                                      const std::vector<bool>& moving);

struct InstanceAccuracy {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::uint16_t id = 0;
  std::string category, name;
  int moving_frames = 0;  // frames where it is in view and moves
  int rest_frames = 0;    // frames where it is in view and at rest
  std::int64_t moving_pixels = 0, moving_marked = 0, attributed_fp = 0, rest_pixels = 0, rest_marked = 0;
  double recall = kNaN, precision = kNaN, rest_marked_fraction = kNaN;
  // After each moving -> rest transition (frame index of the first frame at rest): frames until the marked share
  // first drops below kReleasedFraction; -1 when it never does before the next motion or the end.
  std::vector<std::pair<int, int>> releases;  // (first rest frame, frames until released)
};

class InstanceAccuracyAccumulator {
 public:
  // A marked share below this counts as released (a few superpixels at the outline may stay marked for a frame).
  static constexpr double kReleasedFraction = 0.05;
  // frame: the frame's index in the sequence (frames must come in increasing order).
  void add(int frame, const cv::Mat& predicted, const cv::Mat& instances, const std::vector<bool>& moving);
  // Names per id (from the ground truth), for the summary.
  void describe(std::uint16_t id, std::string category, std::string name);
  std::vector<InstanceAccuracy> summary() const;
  bool empty() const { return frames_ == 0; }

 private:
  struct Track {
    InstanceAccuracy acc;
    bool was_moving = false;
    int pending_stop = -1;  // first rest frame of a stop not yet released
  };
  std::map<std::uint16_t, Track> tracks_;
  int frames_ = 0;
};

// [{"id", "class", "name", "moving_frames", "rest_frames", "recall", "precision", "rest_marked_fraction",
//   "releases": [{"first_rest_frame", "frames_to_release"}]}] (NaN becomes null).
nlohmann::json toJson(const std::vector<InstanceAccuracy>& accuracy);

}  // namespace amos::eval
