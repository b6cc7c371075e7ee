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

TEST(BaselineHistory, WithAMinimumTheOldestFrameServesWhileTheHistoryFills) {
  auto pose = [](double x) { return poseAt({x, 0, 0}); };
  const cv::Mat depth(2, 2, CV_32F, cv::Scalar(1));
  BaselineHistory history(4, 2);
  history.add({depth, cv::Mat(), {}, pose(0)});
  EXPECT_EQ(history.baseline(), nullptr);  // one frame back: the last frame, compared anyway
  history.add({depth, cv::Mat(), {}, pose(1)});
  ASSERT_NE(history.baseline(), nullptr);
  EXPECT_TRUE(history.baseline()->T_cw.isApprox(pose(0)));
  history.add({depth, cv::Mat(), {}, pose(2)});
  history.add({depth, cv::Mat(), {}, pose(3)});
  history.add({depth, cv::Mat(), {}, pose(4)});
  EXPECT_TRUE(history.baseline()->T_cw.isApprox(pose(1)));  // full: the frame 4 back, as without the minimum
  history.clear();
  history.add({depth, cv::Mat(), {}, pose(5)});
  EXPECT_EQ(history.baseline(), nullptr);
  history.add({depth, cv::Mat(), {}, pose(6)});
  EXPECT_TRUE(history.baseline()->T_cw.isApprox(pose(5)));
  // A minimum of 0, 1 or at least the length is no minimum.
  for (const int min_frames : {0, 1, 4, 5}) {
    BaselineHistory plain(4, min_frames);
    for (int k = 0; k < 3; ++k) plain.add({depth, cv::Mat(), {}, pose(k)});
    EXPECT_EQ(plain.baseline(), nullptr) << min_frames;
  }
}

}  // namespace
}  // namespace amos::dynamic
