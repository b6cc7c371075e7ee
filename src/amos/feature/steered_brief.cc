#include "amos/feature/steered_brief.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>

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

SteeredBrief::SteeredBrief(unsigned seed) : pattern_(makeGaussianBriefPattern(seed)) {}

void SteeredBrief::compute(const cv::Mat& smoothed, int x, int y, float angle_deg, std::uint8_t* out) const {
  const double angle = angle_deg * M_PI / 180.0;
  const float c = static_cast<float>(std::cos(angle)), s = static_cast<float>(std::sin(angle));
  const std::uint8_t* center = smoothed.ptr<std::uint8_t>(y) + x;
  const int step = static_cast<int>(smoothed.step1());
  // Pattern point (px, py) is read at the image offset (px c - py s, px s + py c).
  auto sample = [&](int px, int py) {
    const int u = cvRound(px * c - py * s), v = cvRound(px * s + py * c);
    return center[v * step + u];
  };
  const BriefPair* pair = pattern_.data();
  for (int byte = 0; byte < kDescriptorBytes; ++byte) {
    int value = 0;
    for (int bit = 0; bit < 8; ++bit, ++pair)
      value |= (sample(pair->x1, pair->y1) < sample(pair->x2, pair->y2) ? 1 : 0) << bit;
    out[byte] = static_cast<std::uint8_t>(value);
  }
}

}  // namespace amos::feature
