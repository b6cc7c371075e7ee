#pragma once
// Evidence that a map point lies on a moving object (paper Sec. III-C: points that keep landing in dynamic
// regions are culled). A projection into the frame's dynamic mask only counts when the frame's depth at that
// pixel says the point is visible there: a static point merely hidden behind a passing person projects into the
// person's mask too, but the measured depth is then well in front of it.
#include <opencv2/core.hpp>

namespace amos::tracking {

enum class MaskEvidence {
  kNone,      // no mask, outside the image, or the point is occluded by something nearer: says nothing
  kStatic,    // visible where the mask says static
  kDynamic,   // visible (or depth unknown) where the mask says dynamic
};

// mask: CV_8U (non-zero = dynamic); depth: CV_32F metres (may be empty: depth unknown); (u, v) the projection,
// z the point's depth in the camera. The point counts as occluded when the measured depth is nearer than
// z - max(min_gap_m, relative_gap * z) (sensor noise grows with depth).
MaskEvidence maskEvidence(const cv::Mat& mask, const cv::Mat& depth, double u, double v, double z,
                          double min_gap_m = 0.1, double relative_gap = 0.05);

}  // namespace amos::tracking
