#pragma once
// ORB features on a scale pyramid, spread evenly over the image (ORB-SLAM2-style cell FAST with a threshold
// fallback, then quadtree distribution), oriented by intensity centroid, with 256-bit rBRIEF descriptors.
#include <opencv2/core.hpp>

#include <vector>

#include "amos/feature/orientation.h"
#include "amos/feature/steered_brief.h"

namespace amos::feature {

struct OrbOptions {
  int num_features = 1000;      // ORBextractor.nFeatures
  double scale_factor = 1.2;    // ORBextractor.scaleFactor
  int num_levels = 8;           // ORBextractor.nLevels
  int ini_fast_threshold = 20;  // ORBextractor.iniThFAST
  int min_fast_threshold = 7;   // ORBextractor.minThFAST
  // Throws core::InvalidOption naming the member whose value is invalid.
  void check() const;
};

class OrbExtractor {
 public:
  explicit OrbExtractor(const OrbOptions& options);
  // With another descriptor test pattern (kDescriptorBits pairs within radius 15), e.g. to compare patterns.
  OrbExtractor(const OrbOptions& options, std::vector<BriefPair> pattern);

  // gray: CV_8UC1. Keypoints are in level-0 pixel coordinates (distorted, as detected), with octave, angle (deg)
  // and size set; descriptors is N x 32 CV_8U, row i belongs to keypoint i. Deterministic for a given image.
  // Optional mask (CV_8UC1, 0 = do not detect there) restricts detection. extract() keeps no state between calls,
  // so one extractor can serve several threads. Throws core::Error on an empty/non-8UC1 image or a mask of
  // another size or type.
  void extract(const cv::Mat& gray, std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors,
               const cv::Mat& mask = cv::Mat()) const;

  const OrbOptions& options() const { return options_; }
  // scale of level l relative to level 0 (scale_factor^l), and its square / inverses, as tracking needs them.
  const std::vector<float>& scaleFactors() const { return scale_; }
  const std::vector<float>& levelSigma2() const { return sigma2_; }
  const std::vector<float>& invLevelSigma2() const { return inv_sigma2_; }
  // How many keypoints each level aims for (geometric in 1 / scale_factor, summing to num_features).
  const std::vector<int>& featuresPerLevel() const { return features_per_level_; }
  // Reflected border around each pyramid level: room for the radius-15 orientation and descriptor patches of
  // keypoints detected right at the level's edge.
  static constexpr int kLevelBorder = 19;
  static constexpr int kPatchSize = 31;

 private:
  OrbOptions options_;
  std::vector<float> scale_, sigma2_, inv_sigma2_;
  std::vector<int> features_per_level_;
  IntensityCentroid centroid_;
  SteeredBrief brief_;
};

}  // namespace amos::feature
