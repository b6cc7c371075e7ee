#pragma once
// Hamming distance between 256-bit ORB descriptors (rows of a N x 32 CV_8U matrix) and brute-force matching.
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace amos::feature {

// Distance thresholds used throughout ORB-style matching (bits out of 256).
inline constexpr int kDescriptorDistanceHigh = 100;
inline constexpr int kDescriptorDistanceLow = 50;

// Hamming distance between two 32-byte descriptors (pointers to their first byte).
int hammingDistance(const std::uint8_t* a, const std::uint8_t* b);
inline int hammingDistance(const cv::Mat& a, int row_a, const cv::Mat& b, int row_b) {
  return hammingDistance(a.ptr<std::uint8_t>(row_a), b.ptr<std::uint8_t>(row_b));
}

struct BruteForceMatch {
  int query = -1, train = -1, distance = 0;
};

// For every row of `query`, the nearest row of `train`; kept when distance <= max_distance and
// best < ratio * second best (Lowe's test). Each train row is used at most once (the closer query wins).
std::vector<BruteForceMatch> matchBruteForce(const cv::Mat& query, const cv::Mat& train, int max_distance, float ratio);

}  // namespace amos::feature
