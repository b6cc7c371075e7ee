#pragma once
// What `amos-slam run --save-masks` leaves behind besides the trajectory, for judging the dynamic front end:
//   masks/<rgb time stamp>.png     the final dynamic mask of every processed frame, 8-bit, 255 = dynamic
//   overlays/<rgb time stamp>.png  for a few evenly spaced frames: the colour image with the dynamic mask tinted
//                                  red, the prior (segmentation) mask outlined yellow and, when the sequence has
//                                  ground truth, the true movers outlined green
// Each image is written under a temporary name and renamed (io/atomic_file.h).
#include <opencv2/core.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace amos::report {

// `count` frame indices spread evenly over [0, total): the middles of `count` equal slices (all frames when
// total <= count).
std::vector<std::size_t> evenlySpacedFrames(std::size_t total, std::size_t count);

// The overlay described above (CV_8UC3, the colour image's size). Any mask may be empty (= none).
cv::Mat renderMaskOverlay(const cv::Mat& bgr, const cv::Mat& dynamic_mask, const cv::Mat& prior_mask,
                          const cv::Mat& truth_mask, const std::string& caption);

// The file stem a frame's outputs are named by: the RGB image's own stem (its time stamp in TUM/Bonn layouts).
std::string frameStem(const std::string& rgb_file);

class MaskOutputWriter {
 public:
  // Creates <dir>/masks and <dir>/overlays; throws core::Error when it cannot.
  MaskOutputWriter(const std::string& dir, std::size_t total_frames, std::size_t overlay_count);
  // Frame `index` (0-based position in the run). An empty dynamic mask (mode none) is written as all static.
  void add(std::size_t index, const std::string& rgb_file, const cv::Mat& bgr, const cv::Mat& dynamic_mask,
           const cv::Mat& prior_mask, const cv::Mat& truth_mask);
  std::size_t masksWritten() const { return masks_written_; }
  std::size_t overlaysWritten() const { return overlays_written_; }

 private:
  std::string masks_dir_, overlays_dir_;
  std::vector<std::size_t> overlay_frames_;  // sorted
  std::size_t masks_written_ = 0, overlays_written_ = 0;
};

}  // namespace amos::report
