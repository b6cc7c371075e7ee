#pragma once
// 256-bit binary descriptor steered by the keypoint angle (steered BRIEF as in ORB, Rublee et al. 2011).
// Test patterns are our own: by default the learned table of learned_brief_pattern.h (unbiased, decorrelated
// tests, like ORB's rBRIEF); alternatively point pairs drawn from an isotropic Gaussian (sigma = patch size / 5,
// Calonder et al.'s "G II" BRIEF sampling) with a fixed seed. Points lie inside the radius-15 disc, so every
// rotation of the pattern stays inside the 31x31 patch.
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace amos::feature {

struct BriefPair {
  int x1, y1, x2, y2;  // offsets from the keypoint, pixels
};

inline constexpr int kDescriptorBytes = 32;
inline constexpr int kDescriptorBits = 8 * kDescriptorBytes;

// Deterministic for a seed on every platform (raw mt19937 output and our own Box-Muller transform). Pairs are
// distinct, never compare a point with itself, and lie within `radius` of the centre.
std::vector<BriefPair> makeGaussianBriefPattern(unsigned seed, int num_pairs = kDescriptorBits, int radius = 15);

class SteeredBrief {
 public:
  static constexpr unsigned kDefaultSeed = 20240531u;
  // The learned pattern (learnedBriefPattern()).
  SteeredBrief();
  // A Gaussian pattern from this seed (makeGaussianBriefPattern).
  explicit SteeredBrief(unsigned seed);
  // Any pattern of exactly kDescriptorBits pairs within radius 15 (e.g. a learned one).
  explicit SteeredBrief(std::vector<BriefPair> pattern);
  const std::vector<BriefPair>& pattern() const { return pattern_; }
  // Pixels within 15 of (x, y) must be readable in `smoothed` (CV_8UC1, e.g. a blurred padded pyramid level).
  // Bit i (byte i / 8, bit i % 8, least significant first) is I(a_i) < I(b_i), with a_i, b_i rotated by angle.
  void compute(const cv::Mat& smoothed, int x, int y, float angle_deg, std::uint8_t* out) const;

 private:
  std::vector<BriefPair> pattern_;
  // The pattern as point lists, first points then second points of each pair (for the rotation loop).
  std::vector<float> xs_, ys_;
};

}  // namespace amos::feature
