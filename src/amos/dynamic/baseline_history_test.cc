#include "amos/dynamic/baseline_history.h"

#include <gtest/gtest.h>

#include "amos/dynamic/test_scenes.h"

namespace amos::dynamic {
namespace {

TEST(BaselineHistory, GivesTheFrameThatManyBackAndStartsAgainAfterALoss) {
  auto pose = [](double x) { return poseAt({x, 0, 0}); };
  const cv::Mat depth(2, 2, CV_32F, cv::Scalar(1));
  for (const int off : {0, 1}) {
    BaselineHistory none(off);
    for (int k = 0; k < 3; ++k) none.add({depth, cv::Mat(), {}, pose(k)});
    EXPECT_EQ(none.baseline(), nullptr) << off;
  }
  BaselineHistory history(3);
  history.add({depth, cv::Mat(), {}, pose(0)});
  history.add({depth, cv::Mat(), {}, pose(1)});
  EXPECT_EQ(history.baseline(), nullptr);
  history.add({depth, cv::Mat(), {}, pose(2)});
  ASSERT_NE(history.baseline(), nullptr);
  EXPECT_TRUE(history.baseline()->T_cw.isApprox(pose(0)));
  history.add({depth, cv::Mat(), {}, pose(3)});
  EXPECT_TRUE(history.baseline()->T_cw.isApprox(pose(1)));
  history.clear();
  EXPECT_EQ(history.baseline(), nullptr);
}

}  // namespace
}  // namespace amos::dynamic
