#pragma once
// The small views of a frame that the evidence functions take instead of long parameter lists (references, valid
// while the frame is; nothing is copied).
#include <opencv2/core.hpp>

#include "amos/core/camera.h"
#include "amos/core/pose.h"

namespace amos::evidence {

// A depth image (CV_32F metres, 0 = none) and the pose it was taken at.
struct PosedDepth {
  const cv::Mat& depth;
  const core::SE3& T_cw;
};

// A frame's gray (CV_8UC1) and depth images and its pose.
struct PosedImages {
  const cv::Mat& gray;
  const cv::Mat& depth;
  const core::SE3& T_cw;
};

// A superpixel label image (CV_32S) and its number of labels.
struct SuperpixelLabels {
  const cv::Mat& labels;
  int count;
};

}  // namespace amos::evidence
