#include "amos/feature/orb_extractor.h"

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <utility>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/feature/fast_cells.h"
#include "amos/feature/image_pyramid.h"
#include "amos/feature/quadtree_distribution.h"

namespace amos::feature {

void OrbOptions::check() const {
  core::requireOption(num_features > 0, core::option(num_features, "num_features"),
                      fmt::format("must be a positive number of features, got {}", num_features));
  core::requireOption(std::isfinite(scale_factor) && scale_factor > 1.0 && scale_factor <= 4.0,
                      core::option(scale_factor, "scale_factor"),
                      fmt::format("must be in (1, 4], got {}", scale_factor));
  core::requireOption(num_levels >= 1 && num_levels <= 32, core::option(num_levels, "num_levels"),
                      fmt::format("must be in [1, 32], got {}", num_levels));
  core::requireOption(ini_fast_threshold >= 1 && ini_fast_threshold <= 254,
                      core::option(ini_fast_threshold, "ini_fast_threshold"),
                      fmt::format("must be in [1, 254], got {}", ini_fast_threshold));
  core::requireOption(
      min_fast_threshold >= 1 && min_fast_threshold <= ini_fast_threshold,
      core::option(min_fast_threshold, "min_fast_threshold"),
      fmt::format("must be in [1, ini_fast_threshold = {}], got {}", ini_fast_threshold, min_fast_threshold),
      {core::option(ini_fast_threshold, "ini_fast_threshold")});
}

namespace {
constexpr int kFastCellSize = 30;
constexpr int kBlurSize = 7;
constexpr double kBlurSigma = 2.0;
}  // namespace

OrbExtractor::OrbExtractor(const OrbOptions& options) : options_(options), centroid_(kPatchSize / 2) {
  options_.check();
  const int levels = options_.num_levels;
  scale_.resize(static_cast<size_t>(levels));
  sigma2_.resize(static_cast<size_t>(levels));
  inv_sigma2_.resize(static_cast<size_t>(levels));
  for (int l = 0; l < levels; ++l) {
    const double s = std::pow(options_.scale_factor, l);
    scale_[static_cast<size_t>(l)] = static_cast<float>(s);
    sigma2_[static_cast<size_t>(l)] = static_cast<float>(s * s);
    inv_sigma2_[static_cast<size_t>(l)] = static_cast<float>(1.0 / (s * s));
  }
  // Level l gets a share proportional to (1 / scale_factor)^l, i.e. to its linear size (ORB-SLAM2); the last
  // level takes what rounding left over.
  const double factor = 1.0 / options_.scale_factor;
  double desired = options_.num_features * (1.0 - factor) / (1.0 - std::pow(factor, levels));
  if (levels == 1) desired = options_.num_features;
  int assigned = 0;
  features_per_level_.resize(static_cast<size_t>(levels));
  for (int l = 0; l + 1 < levels; ++l) {
    features_per_level_[static_cast<size_t>(l)] = static_cast<int>(std::lround(desired));
    assigned += features_per_level_[static_cast<size_t>(l)];
    desired *= factor;
  }
  features_per_level_.back() = std::max(options_.num_features - assigned, 0);
}

OrbExtractor::OrbExtractor(const OrbOptions& options, std::vector<BriefPair> pattern) : OrbExtractor(options) {
  brief_ = SteeredBrief(std::move(pattern));
}

void OrbExtractor::extract(const cv::Mat& gray, std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors,
                           const cv::Mat& mask) const {
  core::require(!gray.empty() && gray.type() == CV_8UC1, "OrbExtractor::extract needs a non-empty CV_8UC1 image");
  core::require(mask.empty() || (mask.type() == CV_8UC1 && mask.size() == gray.size()),
                "OrbExtractor::extract: the mask must be CV_8UC1 of the image's size");
  keypoints.clear();
  const PaddedPyramid pyramid(gray, scale_, kLevelBorder);
  const FastCellOptions fast{options_.ini_fast_threshold, options_.min_fast_threshold, kFastCellSize};

  std::vector<cv::KeyPoint> level_keypoints;  // all levels, level coordinates, level-major order
  std::vector<cv::Mat> smoothed(static_cast<size_t>(pyramid.numLevels()));
  for (int l = 0; l < pyramid.numLevels(); ++l) {
    const cv::Size size = pyramid.size(l);
    cv::Mat level_mask;
    if (!mask.empty()) {
      if (l == 0) {
        level_mask = mask;
      } else {
        cv::resize(mask, level_mask, size, 0, 0, cv::INTER_NEAREST);
      }
    }
    std::vector<cv::KeyPoint> corners = detectFastInCells(pyramid.padded(l), kLevelBorder, size, fast, level_mask);
    const std::vector<int> kept =
        distributeQuadtree(corners, cv::Rect2f(0, 0, static_cast<float>(size.width), static_cast<float>(size.height)),
                           features_per_level_[static_cast<size_t>(l)]);
    if (kept.empty()) continue;
    const cv::Mat& padded = pyramid.padded(l);
    for (int i : kept) {
      cv::KeyPoint kp = corners[static_cast<size_t>(i)];
      const int x = static_cast<int>(kp.pt.x) + kLevelBorder, y = static_cast<int>(kp.pt.y) + kLevelBorder;
      kp.angle = centroid_.angleDeg(padded, x, y);  // on the unsmoothed level, as ORB does
      kp.octave = l;
      level_keypoints.push_back(kp);
    }
    // The descriptor compares smoothed intensities, which makes its bits robust to noise (ORB: 7x7, sigma 2).
    cv::GaussianBlur(padded, smoothed[static_cast<size_t>(l)], cv::Size(kBlurSize, kBlurSize), kBlurSigma, kBlurSigma,
                     cv::BORDER_REFLECT_101);
  }

  descriptors.create(static_cast<int>(level_keypoints.size()), kDescriptorBytes, CV_8U);
  keypoints.reserve(level_keypoints.size());
  for (size_t k = 0; k < level_keypoints.size(); ++k) {
    cv::KeyPoint kp = level_keypoints[k];
    const int l = kp.octave;
    brief_.compute(smoothed[static_cast<size_t>(l)], static_cast<int>(kp.pt.x) + kLevelBorder,
                   static_cast<int>(kp.pt.y) + kLevelBorder, kp.angle,
                   descriptors.ptr<std::uint8_t>(static_cast<int>(k)));
    // Level pixel centres map to level 0 as cv::resize samples them, x0 = (x + 0.5) r - 0.5, where r is the
    // level's actual size ratio (rounded level sizes make it differ from scale_factor^l by up to ~0.1%).
    const cv::Size size = pyramid.size(l);
    const float rx = static_cast<float>(gray.cols) / size.width, ry = static_cast<float>(gray.rows) / size.height;
    kp.pt.x = (kp.pt.x + 0.5f) * rx - 0.5f;
    kp.pt.y = (kp.pt.y + 0.5f) * ry - 0.5f;
    kp.size = kPatchSize * scale_[static_cast<size_t>(l)];
    keypoints.push_back(kp);
  }
}

}  // namespace amos::feature
