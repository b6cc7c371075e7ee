#include "amos/feature/brief_pattern_learning.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <set>
#include <tuple>

#include "amos/feature/learned_brief_pattern.h"
#include "amos/testing/shared_data.h"

namespace amos::feature {
namespace {

// Every `step`-th frame (sorted by name) of a shared-data folder, grayscale.
std::vector<cv::Mat> frames(const std::string& folder, size_t step, size_t limit = 1000) {
  const std::filesystem::path dir = std::filesystem::path(testing::dataDir()) / folder / "rgb";
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_directory(dir))
    for (const auto& entry : std::filesystem::directory_iterator(dir)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<cv::Mat> images;
  for (size_t i = 0; i < files.size() && images.size() < limit; i += step)
    images.push_back(cv::imread(files[i].string(), cv::IMREAD_GRAYSCALE));
  return images;
}

TEST(LearnedBriefPattern, IsAValidPatternAndTheDefault) {
  const auto& pattern = learnedBriefPattern();
  ASSERT_EQ(pattern.size(), 256u);
  std::set<std::tuple<int, int, int, int>> seen;
  for (const auto& p : pattern) {
    EXPECT_LE(p.x1 * p.x1 + p.y1 * p.y1, 225);
    EXPECT_LE(p.x2 * p.x2 + p.y2 * p.y2, 225);
    EXPECT_FALSE(p.x1 == p.x2 && p.y1 == p.y2);
    EXPECT_TRUE(seen.insert({p.x1, p.y1, p.x2, p.y2}).second);
  }
  EXPECT_EQ(SteeredBrief().pattern().size(), 256u);
  EXPECT_EQ(SteeredBrief().pattern()[17].y2, pattern[17].y2);
}

TEST(LearnedBriefPattern, BeatsTheGaussianPatternOnHeldOutFrames) {
  // TUM fr2/desk was not used for learning.
  AMOS_REQUIRE_DATA("tum_fr2_desk_first50");
  const std::vector<cv::Mat> held_out = frames("tum_fr2_desk_first50", 10);
  ASSERT_EQ(held_out.size(), 5u);
  const BriefPatternStats learned = evaluateBriefPattern(learnedBriefPattern(), held_out, OrbOptions{}, 5000);
  const BriefPatternStats gaussian =
      evaluateBriefPattern(makeGaussianBriefPattern(SteeredBrief::kDefaultSeed), held_out, OrbOptions{}, 5000);
  EXPECT_EQ(learned.samples, 5000);
  EXPECT_LT(learned.mean_abs_bias, 0.17);
  EXPECT_LT(learned.mean_abs_bias, 0.75 * gaussian.mean_abs_bias);
  EXPECT_LT(learned.mean_abs_correlation, 0.1);
  EXPECT_LT(learned.mean_abs_correlation, 0.75 * gaussian.mean_abs_correlation);

  // What that buys: descriptors of different places rarely come within the matchers' 50-bit threshold.
  const OrbExtractor orb(OrbOptions{});
  std::vector<cv::KeyPoint> ka, kb;
  cv::Mat da, db;
  orb.extract(held_out[0], ka, da);
  orb.extract(held_out[3], kb, db);
  int close = 0, pairs = 0;
  for (int i = 0; i < da.rows; i += 3)
    for (int j = 0; j < db.rows; j += 5, ++pairs)
      close += cv::norm(da.row(i), db.row(j), cv::NORM_HAMMING) < 50 ? 1 : 0;
  EXPECT_LT(close, 0.01 * pairs) << close << " of " << pairs;
}

TEST(BriefPatternLearning, SmallRunImprovesOnItsCandidatePool) {
  AMOS_REQUIRE_DATA("bonn_crowd_dev");
  AMOS_REQUIRE_DATA("tum_fr2_desk_first50");
  const std::vector<cv::Mat> train = frames("bonn_crowd_dev", 90);  // 3 frames
  const std::vector<cv::Mat> held_out = frames("tum_fr2_desk_first50", 25);
  ASSERT_EQ(train.size(), 3u);
  ASSERT_EQ(held_out.size(), 2u);
  BriefLearningOptions options;
  options.candidate_pairs = 2000;
  options.max_samples = 3000;
  const std::vector<BriefPair> pattern = learnBriefPattern(train, OrbOptions{}, options);
  ASSERT_EQ(pattern.size(), 256u);
  EXPECT_EQ(pattern.front().x1, learnBriefPattern(train, OrbOptions{}, options).front().x1);  // deterministic
  const BriefPatternStats learned = evaluateBriefPattern(pattern, held_out, OrbOptions{}, 2000);
  const BriefPatternStats gaussian =
      evaluateBriefPattern(makeGaussianBriefPattern(SteeredBrief::kDefaultSeed), held_out, OrbOptions{}, 2000);
  EXPECT_LT(learned.mean_abs_bias, gaussian.mean_abs_bias);
  EXPECT_LT(learned.mean_abs_correlation, gaussian.mean_abs_correlation);
}

}  // namespace
}  // namespace amos::feature
