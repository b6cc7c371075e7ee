#pragma once
// Learns a steered-BRIEF test pattern from images, the way ORB learned rBRIEF (Rublee et al., ICCV 2011, sec. 4.3):
// over many oriented keypoints, candidate tests are ranked by how close their mean is to 0.5 and picked greedily
// so that each new test is weakly correlated with those already chosen. Uncorrelated, unbiased bits make
// non-matching descriptors differ in about half their bits, so the usual Hamming thresholds (50 / 100 of 256)
// separate matches from non-matches. The committed table (learned_brief_pattern.cc) is this function's output.
#include <opencv2/core.hpp>

#include <vector>

#include "amos/feature/orb_extractor.h"
#include "amos/feature/steered_brief.h"

namespace amos::feature {

struct BriefLearningOptions {
  int num_pairs = kDescriptorBits;
  int candidate_pairs = 6000;  // pool drawn from the radius-15 disc (half Gaussian, half uniform)
  unsigned seed = 7;
  int max_samples = 40000;  // oriented keypoints used for the statistics (spread over the images)
  double initial_max_correlation = 0.2;
  double correlation_step = 0.025;  // the bound is relaxed by this until num_pairs tests are found
};

// Statistics of a pattern on oriented keypoints (for learning and for tests).
struct BriefPatternStats {
  double mean_abs_bias = 0;         // mean over tests of |P(bit = 1) - 0.5|
  double mean_abs_correlation = 0;  // mean over test pairs of |correlation|
  int samples = 0;
};

// gray_images: CV_8UC1 images; keypoints are found with an OrbExtractor(orb) and their descriptors patches read
// exactly as SteeredBrief::compute reads them. Deterministic.
std::vector<BriefPair> learnBriefPattern(const std::vector<cv::Mat>& gray_images, const OrbOptions& orb,
                                         const BriefLearningOptions& options = {});

BriefPatternStats evaluateBriefPattern(const std::vector<BriefPair>& pattern, const std::vector<cv::Mat>& gray_images,
                                       const OrbOptions& orb, int max_samples = 20000);

}  // namespace amos::feature
