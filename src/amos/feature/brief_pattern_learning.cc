#include "amos/feature/brief_pattern_learning.h"

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <tuple>

#include "amos/core/error.h"
#include "amos/core/popcnt_clones.h"
#include "amos/feature/image_pyramid.h"

namespace amos::feature {

namespace {

constexpr int kRadius = 15;

// Test outcomes of many candidate tests on many keypoints: bits(test) is a bitset over the samples.
class BitTable {
 public:
  BitTable(int tests, int samples)
      : words_((samples + 63) / 64), samples_(samples), data_(static_cast<size_t>(tests) * words_, 0) {}
  void set(int test, int sample) {
    data_[static_cast<size_t>(test) * words_ + sample / 64] |= std::uint64_t{1} << (sample % 64);
  }
  const std::uint64_t* row(int test) const { return data_.data() + static_cast<size_t>(test) * words_; }
  int words() const { return words_; }
  int samples() const { return samples_; }

 private:
  int words_, samples_;
  std::vector<std::uint64_t> data_;
};

AMOS_POPCNT_CLONES int countOnes(const std::uint64_t* a, int words) {
  int n = 0;
  for (int w = 0; w < words; ++w) n += __builtin_popcountll(a[w]);
  return n;
}

AMOS_POPCNT_CLONES int countBoth(const std::uint64_t* a, const std::uint64_t* b, int words) {
  int n = 0;
  for (int w = 0; w < words; ++w) n += __builtin_popcountll(a[w] & b[w]);
  return n;
}

// Oriented keypoints of the images, each with its smoothed pyramid level, read as SteeredBrief::compute reads
// them; `visit(smoothed, x, y, angle_deg)` is called for an even spread of at most max_samples of them.
template <typename Visit>
int forEachSample(const std::vector<cv::Mat>& images, const OrbOptions& orb_options, int max_samples, Visit visit) {
  const OrbExtractor orb(orb_options);
  const int per_image = std::max(1, max_samples / std::max<int>(1, static_cast<int>(images.size())));
  int samples = 0;
  for (const cv::Mat& image : images) {
    core::require(image.type() == CV_8UC1, "learnBriefPattern needs CV_8UC1 images");
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    orb.extract(image, keypoints, descriptors);
    const PaddedPyramid pyramid(image, orb.scaleFactors(), OrbExtractor::kLevelBorder);
    std::vector<cv::Mat> smoothed(static_cast<size_t>(pyramid.numLevels()));
    for (int l = 0; l < pyramid.numLevels(); ++l)
      cv::GaussianBlur(pyramid.padded(l), smoothed[static_cast<size_t>(l)], cv::Size(7, 7), 2.0, 2.0,
                       cv::BORDER_REFLECT_101);
    const size_t stride = std::max<size_t>(1, keypoints.size() / static_cast<size_t>(per_image));
    int taken = 0;
    for (size_t k = 0; k < keypoints.size() && taken < per_image && samples < max_samples; k += stride) {
      const cv::KeyPoint& kp = keypoints[k];
      const cv::Size size = pyramid.size(kp.octave);
      // Back to level pixels: the inverse of the extractor's x0 = (x + 0.5) r - 0.5.
      const float rx = static_cast<float>(image.cols) / size.width, ry = static_cast<float>(image.rows) / size.height;
      const int x = static_cast<int>(std::lround((kp.pt.x + 0.5f) / rx - 0.5f));
      const int y = static_cast<int>(std::lround((kp.pt.y + 0.5f) / ry - 0.5f));
      visit(smoothed[static_cast<size_t>(kp.octave)], x + OrbExtractor::kLevelBorder, y + OrbExtractor::kLevelBorder,
            kp.angle);
      ++taken;
      ++samples;
    }
  }
  return samples;
}

// Outcomes of `tests` on the samples, computed 256 tests at a time with SteeredBrief itself.
BitTable measureTests(const std::vector<BriefPair>& tests, const std::vector<cv::Mat>& images, const OrbOptions& orb,
                      int max_samples) {
  const int chunks = (static_cast<int>(tests.size()) + kDescriptorBits - 1) / kDescriptorBits;
  std::vector<SteeredBrief> briefs;
  for (int c = 0; c < chunks; ++c) {
    std::vector<BriefPair> chunk(
        tests.begin() + c * kDescriptorBits,
        tests.begin() + std::min<int>(static_cast<int>(tests.size()), (c + 1) * kDescriptorBits));
    chunk.resize(kDescriptorBits, BriefPair{0, 0, 1, 0});  // padding tests, ignored below
    briefs.emplace_back(std::move(chunk));
  }
  BitTable table(static_cast<int>(tests.size()), max_samples);
  std::uint8_t descriptor[kDescriptorBytes];
  int sample = 0;
  forEachSample(images, orb, max_samples, [&](const cv::Mat& smoothed, int x, int y, float angle) {
    for (int c = 0; c < chunks; ++c) {
      briefs[static_cast<size_t>(c)].compute(smoothed, x, y, angle, descriptor);
      for (int b = 0; b < kDescriptorBits; ++b) {
        const int test = c * kDescriptorBits + b;
        if (test < static_cast<int>(tests.size()) && (descriptor[b / 8] >> (b % 8) & 1)) table.set(test, sample);
      }
    }
    ++sample;
  });
  BitTable trimmed(static_cast<int>(tests.size()), sample);
  for (int t = 0; t < static_cast<int>(tests.size()); ++t)
    for (int s = 0; s < sample; ++s)
      if (table.row(t)[s / 64] >> (s % 64) & 1) trimmed.set(t, s);
  return trimmed;
}

// Candidate tests: distinct pairs of distinct integer points in the radius-15 disc, half drawn from the BRIEF
// Gaussian (more tests near the centre, where the patch is most stable) and half uniform (ORB's pool).
std::vector<BriefPair> candidateTests(int count, unsigned seed) {
  std::vector<BriefPair> gaussian = makeGaussianBriefPattern(seed, count / 2, kRadius);
  std::mt19937 rng(seed + 1);
  std::set<std::tuple<int, int, int, int>> seen;
  for (const BriefPair& p : gaussian)
    seen.insert(std::min(std::make_tuple(p.x1, p.y1, p.x2, p.y2), std::make_tuple(p.x2, p.y2, p.x1, p.y1)));
  std::vector<BriefPair> tests = gaussian;
  auto uniformPoint = [&](int& x, int& y) {
    do {
      x = static_cast<int>(rng() % (2 * kRadius + 1)) - kRadius;
      y = static_cast<int>(rng() % (2 * kRadius + 1)) - kRadius;
    } while (x * x + y * y > kRadius * kRadius);
  };
  while (static_cast<int>(tests.size()) < count) {
    BriefPair p{};
    uniformPoint(p.x1, p.y1);
    uniformPoint(p.x2, p.y2);
    if (p.x1 == p.x2 && p.y1 == p.y2) continue;
    if (!seen.insert(std::min(std::make_tuple(p.x1, p.y1, p.x2, p.y2), std::make_tuple(p.x2, p.y2, p.x1, p.y1))).second)
      continue;
    tests.push_back(p);
  }
  return tests;
}

double correlation(const BitTable& table, int a, int b, const std::vector<double>& mean) {
  const double n = table.samples();
  const double both = countBoth(table.row(a), table.row(b), table.words()) / n;
  const double va = mean[static_cast<size_t>(a)] * (1 - mean[static_cast<size_t>(a)]);
  const double vb = mean[static_cast<size_t>(b)] * (1 - mean[static_cast<size_t>(b)]);
  return (both - mean[static_cast<size_t>(a)] * mean[static_cast<size_t>(b)]) / std::sqrt(va * vb);
}

}  // namespace

std::vector<BriefPair> learnBriefPattern(const std::vector<cv::Mat>& gray_images, const OrbOptions& orb,
                                         const BriefLearningOptions& options) {
  core::require(!gray_images.empty(), "learnBriefPattern needs images");
  core::require(options.candidate_pairs >= options.num_pairs && options.num_pairs > 0,
                "learnBriefPattern needs at least num_pairs candidates");
  const std::vector<BriefPair> candidates = candidateTests(options.candidate_pairs, options.seed);
  const BitTable table = measureTests(candidates, gray_images, orb, options.max_samples);
  core::require(table.samples() >= 100, fmt::format("learnBriefPattern found only {} keypoints", table.samples()));

  std::vector<double> mean(candidates.size());
  std::vector<int> order;
  for (size_t t = 0; t < candidates.size(); ++t) {
    mean[t] = static_cast<double>(countOnes(table.row(static_cast<int>(t)), table.words())) / table.samples();
    if (mean[t] > 0 && mean[t] < 1) order.push_back(static_cast<int>(t));  // constant tests carry nothing
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return std::abs(mean[static_cast<size_t>(a)] - 0.5) < std::abs(mean[static_cast<size_t>(b)] - 0.5);
  });

  // Greedy: most balanced first, each new test weakly correlated with every chosen one; relax the bound until
  // enough tests qualify.
  for (double bound = options.initial_max_correlation; bound <= 1.0 + 1e-9; bound += options.correlation_step) {
    std::vector<int> chosen;
    for (int t : order) {
      bool independent = true;
      for (int c : chosen) {
        if (std::abs(correlation(table, t, c, mean)) >= bound) {
          independent = false;
          break;
        }
      }
      if (!independent) continue;
      chosen.push_back(t);
      if (static_cast<int>(chosen.size()) == options.num_pairs) {
        std::vector<BriefPair> pattern;
        for (int c : chosen) pattern.push_back(candidates[static_cast<size_t>(c)]);
        return pattern;
      }
    }
  }
  throw core::Error("learnBriefPattern: not enough informative candidate tests");
}

BriefPatternStats evaluateBriefPattern(const std::vector<BriefPair>& pattern, const std::vector<cv::Mat>& gray_images,
                                       const OrbOptions& orb, int max_samples) {
  const BitTable table = measureTests(pattern, gray_images, orb, max_samples);
  BriefPatternStats stats;
  stats.samples = table.samples();
  if (stats.samples == 0) return stats;
  std::vector<double> mean(pattern.size());
  for (size_t t = 0; t < pattern.size(); ++t) {
    mean[t] = static_cast<double>(countOnes(table.row(static_cast<int>(t)), table.words())) / table.samples();
    stats.mean_abs_bias += std::abs(mean[t] - 0.5) / static_cast<double>(pattern.size());
  }
  double sum = 0;
  int pairs = 0;
  for (size_t a = 0; a < pattern.size(); ++a)
    for (size_t b = a + 1; b < pattern.size(); ++b) {
      if (mean[a] <= 0 || mean[a] >= 1 || mean[b] <= 0 || mean[b] >= 1) {
        sum += 1.0;  // a constant bit is as useless as a fully correlated one
      } else {
        sum += std::abs(correlation(table, static_cast<int>(a), static_cast<int>(b), mean));
      }
      ++pairs;
    }
  stats.mean_abs_correlation = pairs > 0 ? sum / pairs : 0.0;
  return stats;
}

}  // namespace amos::feature
