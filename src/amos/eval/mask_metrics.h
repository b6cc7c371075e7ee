#pragma once
// Pixel accuracy of a dynamic mask against ground truth (the synthetic sequences' mover masks): precision
// (share of the pixels called dynamic that are dynamic), recall (share of the dynamic pixels called dynamic) and
// IoU, per frame and aggregated over a run. A pixel is positive where a mask is non-zero.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <limits>
#include <vector>

#include <opencv2/core.hpp>

namespace amos::eval {

struct MaskCounts {
  std::int64_t true_positive = 0, false_positive = 0, false_negative = 0, true_negative = 0;
  MaskCounts& operator+=(const MaskCounts& other);
};

// Compares two single-channel CV_8U masks of the same size; throws core::Error otherwise.
MaskCounts compareMasks(const cv::Mat& predicted, const cv::Mat& truth);

// NaN when undefined: precision without a predicted pixel, recall without a true pixel, IoU when both are empty.
double precision(const MaskCounts& c);
double recall(const MaskCounts& c);
double iou(const MaskCounts& c);

struct MaskAccuracy {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  int frames = 0;             // frames compared
  int frames_with_truth = 0;  // of which with at least one true (dynamic) pixel
  MaskCounts total;           // summed over the frames
  // Pooled over every pixel of every frame (a frame weighs by its pixel counts).
  double precision = kNaN, recall = kNaN, iou = kNaN;
  // Share of all pixels marked dynamic (on a static sequence: the false-positive rate).
  double dynamic_fraction = kNaN;
  // Medians of the per-frame values, each over the frames where it is defined (see precision() etc.).
  double median_precision = kNaN, median_recall = kNaN, median_iou = kNaN;
};

// Collects per-frame counts; summary() aggregates them.
class MaskAccuracyAccumulator {
 public:
  // Returns the frame's counts.
  MaskCounts add(const cv::Mat& predicted, const cv::Mat& truth);
  MaskAccuracy summary() const;
  bool empty() const { return per_frame_.empty(); }
  const std::vector<MaskCounts>& perFrame() const { return per_frame_; }

 private:
  std::vector<MaskCounts> per_frame_;
};

// Keys: frames frames_with_truth precision recall iou dynamic_fraction median_precision median_recall median_iou
// true_positive false_positive false_negative (NaN becomes null).
nlohmann::json toJson(const MaskAccuracy& accuracy);

}  // namespace amos::eval
