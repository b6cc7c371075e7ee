#pragma once
// Mask of a detected object that has no learned mask (non-person classes): the pixels of its box that lie at
// the object's depth. The object's depth is the median valid depth of the central half of the box (the centre is
// most likely to be the object, not the background around it).
#include <opencv2/core.hpp>

namespace amos::segmentation {

// depth: CV_32F metres (0 = no depth), may be empty. Returns a box-sized CV_8UC1 0/255 mask: pixels with depth
// within `tolerance` metres of the object depth, small holes closed. The whole box when depth is empty or the
// centre has too little valid depth to tell (better to drop a few static keypoints than keep dynamic ones).
cv::Mat boxDepthMask(const cv::Mat& depth, const cv::Rect& box, float tolerance);

}  // namespace amos::segmentation
