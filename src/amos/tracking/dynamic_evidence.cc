#include "amos/tracking/dynamic_evidence.h"

#include <algorithm>
#include <cmath>

namespace amos::tracking {

MaskEvidence maskEvidence(const cv::Mat& mask, const cv::Mat& depth, double u, double v, double z,
                          double min_gap_m, double relative_gap) {
  if (mask.empty()) return MaskEvidence::kNone;
  const int x = static_cast<int>(std::lround(u)), y = static_cast<int>(std::lround(v));
  if (x < 0 || y < 0 || x >= mask.cols || y >= mask.rows) return MaskEvidence::kNone;
  if (!depth.empty()) {
    const float d = depth.at<float>(y, x);
    if (d > 0 && d < z - std::max(min_gap_m, relative_gap * z)) return MaskEvidence::kNone;  // occluded
  }
  return mask.at<std::uint8_t>(y, x) != 0 ? MaskEvidence::kDynamic : MaskEvidence::kStatic;
}

}  // namespace amos::tracking
