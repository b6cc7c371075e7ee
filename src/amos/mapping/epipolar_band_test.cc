#include "amos/mapping/epipolar_band.h"

#include <gtest/gtest.h>

#include <random>

namespace amos::mapping {
namespace {

std::vector<int> bruteForce(const std::vector<BandPoint>& points, double a, double b, double c) {
  std::vector<int> out;
  const double den = a * a + b * b;
  if (den <= 0) return out;
  for (size_t i = 0; i < points.size(); ++i) {
    const double num = a * points[i].u + b * points[i].v + c;
    if (!(num * num / den >= points[i].max_distance2)) out.push_back(static_cast<int>(i));
  }
  return out;
}

// Keypoints as ORB gives them (some outside the 640 x 480 image, as undistorted ones can be), bounds of 8 octaves.
std::vector<BandPoint> randomKeypoints(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(-40, 680), v(-40, 520);
  std::vector<BandPoint> points;
  for (int i = 0; i < n; ++i) {
    const int octave = static_cast<int>(rng() % 8);
    points.push_back({u(rng), v(rng), 3.84 * std::pow(1.2, 2 * octave)});
  }
  return points;
}

TEST(EpipolarBand, KeepsExactlyTheBruteForcesPointsInIndexOrder) {
  std::mt19937 rng(11);
  const std::vector<BandPoint> points = randomKeypoints(rng, 1500);
  const EpipolarBand band(points);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), through_u(-100, 740), through_v(-100, 580);
  std::vector<int> got;
  size_t total = 0;
  for (int q = 0; q < 3000; ++q) {
    // A line through a random point at a random angle, scaled as F12 rows are (tiny coefficients); every 10th
    // query axis-aligned, where one of a, b is exactly zero.
    const double t = q % 10 == 0 ? (q % 20 == 0 ? 0 : M_PI / 2) : angle(rng);
    const double scale = std::pow(10.0, -static_cast<double>(rng() % 7));
    const double a = scale * std::cos(t), b = scale * std::sin(t);
    const double c = -(a * through_u(rng) + b * through_v(rng));
    band.near(a, b, c, got);
    const std::vector<int> expected = bruteForce(points, a, b, c);
    ASSERT_EQ(got, expected) << "query " << q << ": " << a << " u + " << b << " v + " << c;
    total += got.size();
  }
  EXPECT_GT(total, 3000u * 10);  // the lines did cross keypoints
}

TEST(EpipolarBand, PointsOnTheBoundAndDegenerateLines) {
  // Distance exactly at the bound is out (the test is strict), just inside is in.
  const std::vector<BandPoint> points = {{100, 50, 4.0}, {100, 51.999, 4.0}, {300, 48, 4.0}, {300, 300, 1e6}};
  const EpipolarBand band(points);
  std::vector<int> got;
  band.near(0, 1, -50, got);  // the line v = 50
  EXPECT_EQ(got, (std::vector<int>{0, 1, 3}));
  band.near(0, 0, 1, got);  // no line
  EXPECT_TRUE(got.empty());
  band.near(std::nan(""), 1, 0, got);  // a broken line: what the brute force keeps (every point)
  EXPECT_EQ(got, bruteForce(points, std::nan(""), 1, 0));
  EXPECT_EQ(got.size(), points.size());
  EpipolarBand(std::vector<BandPoint>{}).near(1, 0, 0, got);
  EXPECT_TRUE(got.empty());
}

}  // namespace
}  // namespace amos::mapping
