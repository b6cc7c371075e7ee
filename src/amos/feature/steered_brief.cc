#include "amos/feature/steered_brief.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <set>
#include <tuple>
#include <utility>

#include "amos/core/error.h"
#include "amos/feature/learned_brief_pattern.h"

namespace amos::feature {

std::vector<BriefPair> makeGaussianBriefPattern(unsigned seed, int num_pairs, int radius) {
  std::mt19937 rng(seed);
  const double sigma = (2 * radius + 1) / 5.0;
  constexpr double kTwoPow32 = 4294967296.0;
  // One standard normal pair per call (Box-Muller), from two uniform draws in (0, 1].
  auto gaussianPoint = [&](int& x, int& y) {
    const double u1 = (static_cast<double>(rng()) + 1.0) / kTwoPow32;
    const double u2 = (static_cast<double>(rng()) + 1.0) / kTwoPow32;
    const double r = std::sqrt(-2.0 * std::log(u1)) * sigma;
    x = static_cast<int>(std::lround(r * std::cos(2.0 * M_PI * u2)));
    y = static_cast<int>(std::lround(r * std::sin(2.0 * M_PI * u2)));
    return x * x + y * y <= radius * radius;
  };
  std::vector<BriefPair> pattern;
  std::set<std::tuple<int, int, int, int>> seen;
  while (static_cast<int>(pattern.size()) < num_pairs) {
    BriefPair p{};
    if (!gaussianPoint(p.x1, p.y1) || !gaussianPoint(p.x2, p.y2)) continue;
    if (p.x1 == p.x2 && p.y1 == p.y2) continue;
    // A pair and its swap carry the same information (one bit is the other's complement but for ties).
    const auto key = std::min(std::make_tuple(p.x1, p.y1, p.x2, p.y2), std::make_tuple(p.x2, p.y2, p.x1, p.y1));
    if (!seen.insert(key).second) continue;
    pattern.push_back(p);
  }
  return pattern;
}

SteeredBrief::SteeredBrief() : SteeredBrief(learnedBriefPattern()) {}

SteeredBrief::SteeredBrief(unsigned seed) : SteeredBrief(makeGaussianBriefPattern(seed)) {}

SteeredBrief::SteeredBrief(std::vector<BriefPair> pattern) : pattern_(std::move(pattern)) {
  core::require(static_cast<int>(pattern_.size()) == kDescriptorBits,
                fmt::format("SteeredBrief needs {} point pairs, got {}", kDescriptorBits, pattern_.size()));
  for (const BriefPair& p : pattern_)
    core::require(p.x1 * p.x1 + p.y1 * p.y1 <= 225 && p.x2 * p.x2 + p.y2 * p.y2 <= 225,
                  "SteeredBrief pattern points must lie within radius 15 of the keypoint");
  for (const BriefPair& p : pattern_) {
    xs_.push_back(static_cast<float>(p.x1));
    ys_.push_back(static_cast<float>(p.y1));
  }
  for (const BriefPair& p : pattern_) {
    xs_.push_back(static_cast<float>(p.x2));
    ys_.push_back(static_cast<float>(p.y2));
  }
}

namespace {
// Round to nearest (ties to even) by the float magic-number trick; unlike lrintf it vectorises with plain SSE2.
// Valid for |value| < 2^22, far beyond the +-15 pixel offsets here.
inline int roundSmall(float value) {
  const float shifted = value + 12582912.0f;  // 1.5 * 2^23: the integer ends up in the low mantissa bits
  std::int32_t bits;
  std::memcpy(&bits, &shifted, sizeof bits);
  return bits - 0x4B400000;
}
}  // namespace

void SteeredBrief::compute(const cv::Mat& smoothed, int x, int y, float angle_deg, std::uint8_t* out) const {
  const double angle = angle_deg * M_PI / 180.0;
  const float c = static_cast<float>(std::cos(angle)), s = static_cast<float>(std::sin(angle));
  const std::uint8_t* center = smoothed.ptr<std::uint8_t>(y) + x;
  const int step = static_cast<int>(smoothed.step1());
  // Pattern point (px, py) is read at the image offset (px c - py s, px s + py c).
  constexpr int kPoints = 2 * kDescriptorBits;
  int offsets[kPoints];
  const float* px = xs_.data();
  const float* py = ys_.data();
  for (int i = 0; i < kPoints; ++i)
    offsets[i] = roundSmall(px[i] * s + py[i] * c) * step + roundSmall(px[i] * c - py[i] * s);
  const int* first = offsets;
  const int* second = offsets + kDescriptorBits;
  for (int byte = 0; byte < kDescriptorBytes; ++byte) {
    int value = 0;
    for (int bit = 0; bit < 8; ++bit) {
      const int i = 8 * byte + bit;
      value |= (center[first[i]] < center[second[i]] ? 1 : 0) << bit;
    }
    out[byte] = static_cast<std::uint8_t>(value);
  }
}

}  // namespace amos::feature
