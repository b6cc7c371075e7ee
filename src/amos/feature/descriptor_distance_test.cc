#include "amos/feature/descriptor_distance.h"

#include <gtest/gtest.h>

#include <bitset>
#include <random>

#include "amos/core/error.h"

namespace amos::feature {
namespace {

cv::Mat randomDescriptors(int rows, unsigned seed) {
  std::mt19937 rng(seed);
  cv::Mat d(rows, 32, CV_8UC1);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < 32; ++c) d.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(rng() & 0xFF);
  return d;
}

// Copy of row `row` with `bits` distinct bits flipped (bit positions from the seed).
void flipBits(cv::Mat& d, int row, int bits, unsigned seed) {
  std::mt19937 rng(seed);
  std::bitset<256> flipped;
  while (static_cast<int>(flipped.count()) < bits) {
    const int b = static_cast<int>(rng() % 256);
    if (flipped[b]) continue;
    flipped[b] = true;
    d.at<std::uint8_t>(row, b / 8) ^= static_cast<std::uint8_t>(1u << (b % 8));
  }
}

TEST(HammingDistance, KnownValues) {
  cv::Mat a(1, 32, CV_8UC1, cv::Scalar(0)), b(1, 32, CV_8UC1, cv::Scalar(0));
  EXPECT_EQ(hammingDistance(a, 0, b, 0), 0);
  b.setTo(0xFF);
  EXPECT_EQ(hammingDistance(a, 0, b, 0), 256);
  b.setTo(0);
  b.at<std::uint8_t>(0, 0) = 0x01;   // bit 0
  b.at<std::uint8_t>(0, 13) = 0xF0;  // 4 bits in the second 64-bit word
  b.at<std::uint8_t>(0, 31) = 0x80;  // last bit
  EXPECT_EQ(hammingDistance(a, 0, b, 0), 6);
  // Agrees with OpenCV's own Hamming norm on random rows, and works on unaligned row pointers.
  const cv::Mat r = randomDescriptors(50, 3);
  std::vector<std::uint8_t> shifted(33 + 32);
  for (int i = 0; i + 1 < r.rows; ++i) {
    EXPECT_EQ(hammingDistance(r, i, r, i + 1), static_cast<int>(cv::norm(r.row(i), r.row(i + 1), cv::NORM_HAMMING)));
    std::copy(r.ptr<std::uint8_t>(i), r.ptr<std::uint8_t>(i) + 32, shifted.begin() + 1);
    EXPECT_EQ(hammingDistance(shifted.data() + 1, r.ptr<std::uint8_t>(i + 1)), hammingDistance(r, i, r, i + 1));
  }
}

TEST(MatchBruteForce, FindsPlantedMatches) {
  // Train: 200 random rows. Query: noisy copies (10 flipped bits) of train rows 0, 10, 20, ..., in shuffled
  // order, plus 20 unrelated rows that must stay unmatched at max_distance 50.
  const cv::Mat train = randomDescriptors(200, 1);
  std::vector<int> truth;
  cv::Mat query;
  for (int k = 0; k < 20; ++k) {
    const int t = (k * 70) % 200;  // 0, 70, 140, 10, 80, ... distinct
    truth.push_back(t);
    query.push_back(train.row(t).clone());
    flipBits(query, query.rows - 1, 10, 100 + k);
  }
  query.push_back(randomDescriptors(20, 2));
  const auto matches = matchBruteForce(query, train, kDescriptorDistanceLow, 0.9f);
  ASSERT_EQ(matches.size(), 20u);
  for (const auto& m : matches) {
    ASSERT_LT(m.query, 20);
    EXPECT_EQ(m.train, truth[static_cast<size_t>(m.query)]);
    EXPECT_EQ(m.distance, 10);
  }
}

TEST(MatchBruteForce, RatioTestRejectsAmbiguousMatches) {
  // Train rows 0 and 1 are at distances 8 and 10 from the query: the match passes a 0.9 ratio (8 < 9) but not
  // a 0.8 one (8 >= 8).
  cv::Mat train = randomDescriptors(3, 5);
  cv::Mat query = train.row(0).clone();
  train.row(0).copyTo(train.row(1));
  flipBits(train, 0, 8, 1);
  flipBits(train, 1, 10, 2);
  EXPECT_TRUE(matchBruteForce(query, train, 100, 0.8f).empty());  // 8 >= 0.8 * 10
  const auto m = matchBruteForce(query, train, 100, 0.9f);        // 8 < 9
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].train, 0);
  EXPECT_EQ(m[0].distance, 8);
  EXPECT_TRUE(matchBruteForce(query, train, 7, 0.9f).empty());   // distance above max_distance
  EXPECT_EQ(matchBruteForce(query, train, 8, 0.9f).size(), 1u);  // max_distance is inclusive
}

TEST(MatchBruteForce, EachTrainRowIsUsedOnce) {
  // Two queries whose nearest train row is the same: the closer one keeps it.
  cv::Mat train = randomDescriptors(5, 7);
  cv::Mat query;
  query.push_back(train.row(2).clone());
  query.push_back(train.row(2).clone());
  flipBits(query, 0, 12, 3);
  flipBits(query, 1, 4, 4);
  const auto m = matchBruteForce(query, train, 50, 1.0f);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].query, 1);
  EXPECT_EQ(m[0].train, 2);
  EXPECT_EQ(m[0].distance, 4);
}

TEST(MatchBruteForce, EdgeCases) {
  const cv::Mat d = randomDescriptors(4, 9);
  EXPECT_TRUE(matchBruteForce(cv::Mat(), d, 50, 0.8f).empty());
  EXPECT_TRUE(matchBruteForce(d, cv::Mat(), 50, 0.8f).empty());
  // A single train row: no second neighbour, the ratio test cannot reject.
  const auto m = matchBruteForce(d.row(1), d.row(1), 0, 0.5f);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].distance, 0);
  EXPECT_THROW(matchBruteForce(cv::Mat(3, 16, CV_8UC1), d, 50, 0.8f), core::Error);
}

}  // namespace
}  // namespace amos::feature
