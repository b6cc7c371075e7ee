#pragma once
// Keypoint orientation by intensity centroid (Rosin; ORB, Rublee et al. 2011): the angle of the vector from the
// keypoint to the centroid of the intensities in a circular patch.
#include <opencv2/core.hpp>

#include <vector>

namespace amos::feature {

class IntensityCentroid {
 public:
  explicit IntensityCentroid(int radius = 15);
  int radius() const { return radius_; }
  // Angle in degrees in [0, 360), measured from +x towards +y (image y points down). `image` must have at least
  // radius() valid pixels around (x, y) in every direction (e.g. a PaddedPyramid level).
  float angleDeg(const cv::Mat& image, int x, int y) const;

 private:
  int radius_;
  std::vector<int> half_width_;  // half_width_[v]: the circle spans u in [-w, w] on rows +-v
};

}  // namespace amos::feature
