#include "amos/synth/sensor_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "amos/core/error.h"

namespace amos::synth {
namespace {

TEST(SensorModel, DepthNoiseFollowsNguyenAndIsQuantised) {
  const SensorModel sensor{SensorOptions()};
  for (double z : {1.0, 2.5, 4.0}) {
    const cv::Mat exact(480, 640, CV_32F, cv::Scalar(z)), incidence(480, 640, CV_32F, cv::Scalar(1));
    Random rng(7);
    const cv::Mat d = sensor.measureDepth(exact, incidence, rng);
    double sum = 0, sum2 = 0;
    long n = 0, holes = 0;
    for (int y = 0; y < d.rows; ++y)
      for (int x = 0; x < d.cols; ++x) {
        const std::uint16_t v = d.at<std::uint16_t>(y, x);
        if (v == 0) {
          ++holes;
          continue;
        }
        const double e = v / 5000.0 - z;
        sum += e;
        sum2 += e * e;
        ++n;
      }
    const double sigma = 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4);
    const double std = std::sqrt(sum2 / n - (sum / n) * (sum / n));
    // Quantisation adds (1/5000)^2 / 12 to the variance.
    EXPECT_NEAR(std, std::sqrt(sigma * sigma + 0.0002 * 0.0002 / 12), 0.03 * sigma) << z;
    EXPECT_NEAR(sum / n, 0.0, 3 * sigma / std::sqrt(static_cast<double>(n)) + 1e-5) << z;
    EXPECT_LT(holes, 0.004 * d.total()) << z;  // only the random drop-outs on a flat wall
  }
}

TEST(SensorModel, HolesBeyondRangeAtEdgesAndGrazingAngles) {
  SensorOptions o;
  const SensorModel sensor(o);
  cv::Mat exact(100, 100, CV_32F, cv::Scalar(2.0)), incidence(100, 100, CV_32F, cv::Scalar(1));
  exact(cv::Rect(0, 0, 100, 10)).setTo(6.0);       // beyond 5 m
  exact(cv::Rect(0, 10, 100, 10)).setTo(0.3);      // closer than 0.4 m
  exact(cv::Rect(50, 20, 50, 80)).setTo(3.0);      // a depth edge at x = 49 / 50
  incidence(cv::Rect(0, 90, 40, 10)).setTo(0.05);  // grazing
  Random rng(3);
  const cv::Mat d = sensor.measureDepth(exact, incidence, rng);
  EXPECT_EQ(cv::countNonZero(d(cv::Rect(0, 0, 100, 20))), 0);
  const int edge_valid = cv::countNonZero(d(cv::Rect(49, 25, 2, 60)));
  EXPECT_LT(edge_valid, 0.4 * 120);
  EXPECT_LT(cv::countNonZero(d(cv::Rect(0, 90, 40, 10))), 0.45 * 400);
  EXPECT_GT(cv::countNonZero(d(cv::Rect(10, 30, 30, 50))), 0.99 * 1500);

  o.depth.enabled = false;  // exact mode: quantisation only
  const SensorModel exact_sensor(o);
  const cv::Mat q = exact_sensor.measureDepth(exact, incidence, rng);
  EXPECT_EQ(q.at<std::uint16_t>(50, 20), 10000);
  EXPECT_EQ(q.at<std::uint16_t>(50, 70), 15000);
}

TEST(SensorModel, ColourNoiseHasTheConfiguredSigma) {
  SensorOptions o;
  o.color.blur_sigma_px = 0;
  const SensorModel sensor(o);
  const cv::Mat flat(200, 200, CV_32FC3, cv::Scalar(100, 120, 140));
  Random rng(11);
  const cv::Mat out = sensor.measureColor(flat, rng);
  cv::Scalar mean, stddev;
  cv::meanStdDev(out, mean, stddev);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(mean[c], 100 + 20 * c, 0.1);
    EXPECT_NEAR(stddev[c], std::sqrt(4.0 + 1.0 / 12), 0.1);
  }
}

TEST(SensorModel, OptionsAreChecked) {
  SensorOptions o;
  o.depth.max_range_m = 20;  // 20 m * 5000 does not fit 16 bits
  EXPECT_THROW(o.check(), core::Error);
  o = SensorOptions();
  o.exposure_s = 0.05;  // longer than a frame at 30 Hz
  EXPECT_THROW(o.check(), core::Error);
  EXPECT_NO_THROW(SensorOptions().check());
}

TEST(Random, GaussianTableIsStandardNormal) {
  const GaussianTable t;
  double sum = 0, sum2 = 0;
  for (std::uint32_t i = 0; i < 65536; ++i) {
    sum += t[i];
    sum2 += t[i] * t[i];
  }
  EXPECT_NEAR(sum / 65536, 0.0, 1e-6);
  EXPECT_NEAR(sum2 / 65536, 1.0, 2e-3);
  EXPECT_NEAR(inverseNormalCdf(0.975), 1.959963985, 1e-8);
  EXPECT_NEAR(inverseNormalCdf(0.001), -3.090232306, 1e-8);
  EXPECT_NE(deriveSeed(1, Stream::kRoom), deriveSeed(1, Stream::kMovers));
  EXPECT_NE(deriveSeed(1, Stream::kSensor, 0), deriveSeed(1, Stream::kSensor, 1));
}

}  // namespace
}  // namespace amos::synth
