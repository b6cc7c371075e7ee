#include "amos/feature/orb_extractor.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <bitset>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/testing/shared_data.h"

namespace amos::feature {
namespace {

// First frame of TUM fr2/desk (real texture: desk, keyboard, monitor, books).
cv::Mat tumFrame() {
  const std::filesystem::path dir = testing::dataPath("tum_fr2_desk_first50/rgb");
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_directory(dir))
    for (const auto& entry : std::filesystem::directory_iterator(dir)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) return {};
  return cv::imread(files.front().string(), cv::IMREAD_GRAYSCALE);
}

// Smoothed random blobs: corners everywhere, no image structure to exploit.
cv::Mat syntheticTexture(int width = 640, int height = 480, unsigned seed = 1) {
  std::mt19937 rng(seed);
  cv::Mat img(height, width, CV_8UC1, cv::Scalar(128));
  for (int i = 0; i < 3000; ++i) {
    const cv::Point c(static_cast<int>(rng() % width), static_cast<int>(rng() % height));
    const int r = 2 + static_cast<int>(rng() % 8);
    cv::circle(img, c, r, cv::Scalar(static_cast<double>(rng() % 256)), cv::FILLED, cv::LINE_AA);
  }
  cv::GaussianBlur(img, img, cv::Size(3, 3), 0.8);
  return img;
}

int hamming(const cv::Mat& a, int i, const cv::Mat& b, int j) {
  int d = 0;
  for (int k = 0; k < 32; ++k)
    d += static_cast<int>(std::bitset<8>(a.at<std::uint8_t>(i, k) ^ b.at<std::uint8_t>(j, k)).count());
  return d;
}

// On synthetic texture always; on the real frame when the shared data is there.
TEST(OrbExtractor, KeypointsCoverTheImageAndReachTheTarget) {
  std::vector<cv::Mat> images = {syntheticTexture()};
  if (!testing::missingData("tum_fr2_desk_first50")) images.push_back(tumFrame());
  for (const cv::Mat& image : images) {
    ASSERT_FALSE(image.empty());
    OrbExtractor orb(OrbOptions{});
    std::vector<cv::KeyPoint> kps;
    cv::Mat desc;
    orb.extract(image, kps, desc);
    EXPECT_GE(static_cast<int>(kps.size()), 900);
    EXPECT_LE(static_cast<int>(kps.size()), 1000);
    ASSERT_EQ(desc.rows, static_cast<int>(kps.size()));
    EXPECT_EQ(desc.cols, 32);
    EXPECT_EQ(desc.type(), CV_8U);
    int cells[4][4] = {};
    for (const auto& kp : kps) {
      ASSERT_GE(kp.pt.x, 0.0f);
      ASSERT_GE(kp.pt.y, 0.0f);
      ASSERT_LT(kp.pt.x, image.cols);
      ASSERT_LT(kp.pt.y, image.rows);
      cells[static_cast<int>(kp.pt.y) * 4 / image.rows][static_cast<int>(kp.pt.x) * 4 / image.cols]++;
    }
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) EXPECT_GE(cells[r][c], 10) << "cell " << r << "," << c;
  }
}

TEST(OrbExtractor, ScaleAndLevelBookkeeping) {
  OrbOptions options;
  options.num_features = 1200;
  const OrbExtractor orb(options);
  ASSERT_EQ(orb.scaleFactors().size(), 8u);
  int total = 0;
  for (int l = 0; l < 8; ++l) {
    const double s = std::pow(1.2, l);
    EXPECT_NEAR(orb.scaleFactors()[l], s, 1e-5 * s);
    EXPECT_NEAR(orb.levelSigma2()[l], s * s, 1e-5 * s * s);
    EXPECT_NEAR(orb.invLevelSigma2()[l] * orb.levelSigma2()[l], 1.0, 1e-6);
    if (l > 0) {
      EXPECT_LE(orb.featuresPerLevel()[l], orb.featuresPerLevel()[l - 1]);
    }
    total += orb.featuresPerLevel()[l];
  }
  EXPECT_EQ(total, 1200);
  // Level 0 takes 1200 (1 - 1/1.2) / (1 - 1.2^-8) = 260.8 of them.
  EXPECT_EQ(orb.featuresPerLevel()[0], 261);

  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  orb.extract(syntheticTexture(), kps, desc);
  std::vector<int> per_level(8, 0);
  for (const auto& kp : kps) {
    ASSERT_GE(kp.octave, 0);
    ASSERT_LT(kp.octave, 8);
    per_level[kp.octave]++;
    EXPECT_FLOAT_EQ(kp.size, 31.0f * orb.scaleFactors()[kp.octave]);
    EXPECT_GE(kp.angle, 0.0f);
    EXPECT_LT(kp.angle, 360.0f);
    EXPECT_GE(kp.response, options.min_fast_threshold);
  }
  for (int l = 0; l < 8; ++l) {
    EXPECT_LE(per_level[l], orb.featuresPerLevel()[l]);
    EXPECT_GE(per_level[l], orb.featuresPerLevel()[l] * 8 / 10) << "level " << l;
  }
  // Keypoints come level by level.
  EXPECT_TRUE(std::is_sorted(kps.begin(), kps.end(),
                             [](const cv::KeyPoint& a, const cv::KeyPoint& b) { return a.octave < b.octave; }));
}

TEST(OrbExtractor, CoarseLevelKeypointsMapExactlyToLevelZero) {
  // Level 1 of an image's pyramid is the image resized by 1/1.2, so a keypoint found at level 0 of that resized
  // image must appear at level 1 of the full image, at the same place once both are in full-image coordinates,
  // with the same descriptor.
  const cv::Mat image = syntheticTexture(640, 480, 4);
  const cv::Size level1(533, 400);  // round(640 / 1.2), round(480 / 1.2)
  cv::Mat small;
  cv::resize(image, small, level1, 0, 0, cv::INTER_LINEAR);
  const OrbExtractor orb(OrbOptions{});
  std::vector<cv::KeyPoint> kp_full, kp_small;
  cv::Mat d_full, d_small;
  orb.extract(image, kp_full, d_full);
  orb.extract(small, kp_small, d_small);
  const float rx = 640.0f / 533.0f, ry = 480.0f / 400.0f;
  int tried = 0, found = 0, same_descriptor = 0;
  for (size_t i = 0; i < kp_small.size(); ++i) {
    if (kp_small[i].octave != 0) continue;
    ++tried;
    const cv::Point2f expected((kp_small[i].pt.x + 0.5f) * rx - 0.5f, (kp_small[i].pt.y + 0.5f) * ry - 0.5f);
    for (size_t j = 0; j < kp_full.size(); ++j) {
      if (kp_full[j].octave != 1 || cv::norm(kp_full[j].pt - expected) > 1e-3) continue;
      ++found;
      same_descriptor += hamming(d_small, static_cast<int>(i), d_full, static_cast<int>(j)) == 0 ? 1 : 0;
      EXPECT_FLOAT_EQ(kp_full[j].angle, kp_small[i].angle);
    }
  }
  ASSERT_GT(tried, 100);
  // The two runs select from the same corners with different per-level budgets, so most (not all) coincide.
  EXPECT_GE(found, tried / 2);
  EXPECT_EQ(same_descriptor, found);
}

TEST(OrbExtractor, DescriptorsSurviveRotation) {
  AMOS_REQUIRE_DATA("tum_fr2_desk_first50");
  const cv::Mat image = tumFrame();
  ASSERT_FALSE(image.empty());
  const cv::Point2f center(image.cols / 2.0f, image.rows / 2.0f);
  const double rotation_deg = 30.0;
  const cv::Mat R = cv::getRotationMatrix2D(center, rotation_deg, 1.0);
  cv::Mat rotated;
  cv::warpAffine(image, rotated, R, image.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));

  const OrbExtractor orb(OrbOptions{});
  std::vector<cv::KeyPoint> kp_a, kp_b;
  cv::Mat desc_a, desc_b;
  orb.extract(image, kp_a, desc_a);
  orb.extract(rotated, kp_b, desc_b);

  // Pair each keypoint with the keypoint of the same level nearest to its rotated position.
  int pairs = 0, close = 0, angle_ok = 0;
  for (size_t i = 0; i < kp_a.size(); ++i) {
    const cv::Point2f p = kp_a[i].pt;
    const cv::Point2f q(static_cast<float>(R.at<double>(0, 0) * p.x + R.at<double>(0, 1) * p.y + R.at<double>(0, 2)),
                        static_cast<float>(R.at<double>(1, 0) * p.x + R.at<double>(1, 1) * p.y + R.at<double>(1, 2)));
    // Far enough from the black corners the rotation brings in, so the patch is the same on both sides.
    if (q.x < 40 || q.y < 40 || q.x >= image.cols - 40 || q.y >= image.rows - 40) continue;
    const float radius = 1.5f * orb.scaleFactors()[kp_a[i].octave];
    int best = -1;
    float best_d = radius;
    for (size_t j = 0; j < kp_b.size(); ++j) {
      if (kp_b[j].octave != kp_a[i].octave) continue;
      const float d = static_cast<float>(cv::norm(kp_b[j].pt - q));
      if (d <= best_d) best_d = d, best = static_cast<int>(j);
    }
    if (best < 0) continue;
    ++pairs;
    close += hamming(desc_a, static_cast<int>(i), desc_b, best) < 50 ? 1 : 0;
    // Counter-clockwise on screen is a negative angle in y-down image coordinates.
    float diff = kp_b[best].angle - kp_a[i].angle + static_cast<float>(rotation_deg);
    diff = std::fmod(diff + 540.0f, 360.0f) - 180.0f;
    angle_ok += std::abs(diff) < 10.0f ? 1 : 0;
  }
  ASSERT_GE(pairs, 200);
  EXPECT_GE(close, 0.7 * pairs) << close << " of " << pairs;
  EXPECT_GE(angle_ok, 0.8 * pairs) << angle_ok << " of " << pairs;
}

TEST(OrbExtractor, Deterministic) {
  const OrbExtractor orb(OrbOptions{});
  const cv::Mat image = syntheticTexture(640, 480, 9);
  std::vector<cv::KeyPoint> a, b;
  cv::Mat da, db;
  orb.extract(image, a, da);
  orb.extract(image, b, db);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].pt, b[i].pt);
    EXPECT_EQ(a[i].angle, b[i].angle);
    EXPECT_EQ(a[i].octave, b[i].octave);
    EXPECT_EQ(a[i].response, b[i].response);
  }
  EXPECT_EQ(cv::norm(da, db, cv::NORM_HAMMING), 0.0);
}

TEST(OrbExtractor, HonoursTheMask) {
  const cv::Mat image = syntheticTexture();
  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(255));
  mask(cv::Rect(0, 0, 320, 480)).setTo(0);
  const OrbExtractor orb(OrbOptions{});
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  orb.extract(image, kps, desc, mask);
  EXPECT_GE(static_cast<int>(kps.size()), 800);  // the allowed half is textured enough for most of the target
  for (const auto& kp : kps) EXPECT_GE(kp.pt.x, 320.0f - orb.scaleFactors()[kp.octave]) << kp.pt;
  // A wrong-sized mask is an error, not a silent no-op.
  EXPECT_THROW(orb.extract(image, kps, desc, cv::Mat(10, 10, CV_8UC1, cv::Scalar(1))), core::Error);
}

TEST(OrbExtractor, BlankImageGivesNoKeypoints) {
  const OrbExtractor orb(OrbOptions{});
  std::vector<cv::KeyPoint> kps(3);
  cv::Mat desc;
  orb.extract(cv::Mat(480, 640, CV_8UC1, cv::Scalar(77)), kps, desc);
  EXPECT_TRUE(kps.empty());
  EXPECT_EQ(desc.rows, 0);
  EXPECT_THROW(orb.extract(cv::Mat(), kps, desc), core::Error);
  EXPECT_THROW(orb.extract(cv::Mat(48, 64, CV_8UC3), kps, desc), core::Error);
}

TEST(OrbOptions, CheckNamesTheMemberAtFault) {
  auto message = [](OrbOptions o) {
    try {
      o.check();
    } catch (const core::InvalidOption& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  OrbOptions o;
  EXPECT_EQ(message(o), "");
  o = {};
  o.num_features = 0;
  EXPECT_EQ(message(o), "num_features must be a positive number of features, got 0");
  o = {};
  o.scale_factor = 1.0;
  EXPECT_EQ(message(o), "scale_factor must be in (1, 4], got 1");
  o = {};
  o.num_levels = 0;
  EXPECT_EQ(message(o), "num_levels must be in [1, 32], got 0");
  o = {};
  o.ini_fast_threshold = 0;
  EXPECT_EQ(message(o), "ini_fast_threshold must be in [1, 254], got 0");
  o = {};
  o.min_fast_threshold = 30;  // above iniThFAST
  EXPECT_EQ(message(o), "min_fast_threshold must be in [1, ini_fast_threshold = 20], got 30");
  EXPECT_THROW(OrbExtractor{o}, core::Error);
}

}  // namespace
}  // namespace amos::feature
