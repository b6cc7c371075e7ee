#include "amos/eval/stats.h"

#include <gtest/gtest.h>

#include <cmath>

namespace amos::eval {
namespace {

TEST(ErrorStats, NumpyConventions) {
  const ErrorStats s = computeErrorStats({4.0, 1.0, 3.0, 2.0});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(30.0 / 4.0));
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);  // even count: mean of the two middle values
  EXPECT_DOUBLE_EQ(s.std_dev, std::sqrt(1.25));  // population std (numpy default ddof=0)
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  EXPECT_DOUBLE_EQ(computeErrorStats({5.0, 1.0, 3.0}).median, 3.0);
}

TEST(ErrorStats, EmptyIsNaN) {
  const ErrorStats s = computeErrorStats({});
  EXPECT_EQ(s.count, 0u);
  EXPECT_TRUE(std::isnan(s.rmse) && std::isnan(s.median) && std::isnan(s.max));
}

TEST(ErrorStats, ScaledMultipliesEveryFigure) {
  const ErrorStats s = scaled(computeErrorStats({1.0, 3.0}), 10.0);
  EXPECT_DOUBLE_EQ(s.mean, 20.0);
  EXPECT_DOUBLE_EQ(s.max, 30.0);
  EXPECT_DOUBLE_EQ(s.rmse, 10.0 * std::sqrt(5.0));
}

}  // namespace
}  // namespace amos::eval
