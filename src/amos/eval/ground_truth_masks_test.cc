#include "amos/eval/ground_truth_masks.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "amos/core/error.h"
#include "amos/testing/scratch_dir.h"

namespace amos::eval {
namespace {

namespace fs = std::filesystem;

// Three frames of 4x4 px: instance 1 (a person) fills the top row and moves in frames 0-1; instance 2 (an
// object) fills the bottom row and moves only in frame 2.
fs::path writeSequence(const std::string& name) {
  const fs::path dir = testing::scratchDir(name);
  fs::create_directories(dir / "masks");
  std::ofstream index(dir / "masks.txt");
  index << "# instance masks\n# timestamp filename\n";
  for (int k = 0; k < 3; ++k) {
    cv::Mat m(4, 4, CV_16U, cv::Scalar(0));
    m.row(0).setTo(1);
    m.row(3).setTo(2);
    const std::string stamp = "100.0" + std::to_string(k) + "0000";
    cv::imwrite((dir / "masks" / (stamp + ".png")).string(), m);
    index << stamp << " masks/" << stamp << ".png\n";
  }
  std::ofstream json(dir / "instances.json");
  json << R"({"instances": {"1": {"class": "person", "name": "walker", "moving_frames": [[0, 1]]},
                            "2": {"class": "object", "name": "box", "moving_frames": [[2, 2]]}}})";
  return dir;
}

TEST(GroundTruthMasks, UnionOfTheInstancesMovingInEachFrame) {
  const fs::path dir = writeSequence("gt_masks_union");
  const auto gt = GroundTruthMasks::find(dir.string());
  ASSERT_TRUE(gt.has_value());
  ASSERT_EQ(gt->size(), 3u);
  ASSERT_EQ(gt->instances().size(), 2u);
  EXPECT_EQ(gt->instances()[0].category, "person");
  const cv::Mat frame0 = gt->moverMask(0), frame2 = gt->moverMask(2);
  EXPECT_EQ(cv::countNonZero(frame0.row(0)), 4);
  EXPECT_EQ(cv::countNonZero(frame0), 4);  // the box rests in frame 0
  EXPECT_EQ(cv::countNonZero(frame2.row(3)), 4);
  EXPECT_EQ(cv::countNonZero(frame2), 4);  // the person stands in frame 2
  EXPECT_EQ(gt->instanceMask(1).at<std::uint16_t>(3, 0), 2);
}

TEST(GroundTruthMasks, FindsFramesByTimeStamp) {
  const auto gt = GroundTruthMasks::find(writeSequence("gt_masks_stamps").string());
  ASSERT_TRUE(gt.has_value());
  EXPECT_EQ(gt->frameAt(100.01), 1);
  EXPECT_EQ(gt->frameAt(100.0205), 2);
  EXPECT_EQ(gt->frameAt(99.0), std::nullopt);
  EXPECT_EQ(gt->frameAt(100.015, 0.004), std::nullopt);  // 5 ms from both neighbours
}

TEST(GroundTruthMasks, AbsentWithoutMasksAndMalformedThrows) {
  const fs::path dir = testing::scratchDir("gt_masks_none");
  EXPECT_FALSE(GroundTruthMasks::find(dir.string()).has_value());
  const fs::path bad = writeSequence("gt_masks_bad");
  std::ofstream(bad / "instances.json") << R"({"instances": {"1": {"class": "person"}}})";
  EXPECT_THROW(GroundTruthMasks::find(bad.string()), core::Error);
}

}  // namespace
}  // namespace amos::eval
