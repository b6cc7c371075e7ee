// A run over a bag equals the run over the folder it was written from, pose for pose and byte for byte in the
// trajectory file's format (--deterministic): the bag source changes where the frames come from, nothing else.
#include <gtest/gtest.h>

#include <string>

#include "amos/io/trajectory.h"
#include "amos/run/bag_source.h"
#include "amos/run/sequence_run.h"
#include "amos/run/settings_sections.h"
#include "amos/rosbag/test_bags.h"
#include "amos/testing/shared_data.h"

namespace amos::rosbag {
namespace {

std::string trajectoryText(const run::SequenceRunResult& result) {
  std::string text;
  for (const io::StampedPose& pose : result.trajectory) text += io::formatTumPose(pose);
  return text;
}

run::SequenceRunResult runOn(const std::string& sequence, const std::string& config, const std::string& mode) {
  run::SequenceRunOptions options;
  options.sequence_dir = sequence;
  options.mode = mode;
  options.deterministic = true;
  options.models_dir = testing::modelsDir();
  if (run::isBagFile(sequence)) {
    options.source = run::FrameSourceKind::kBag;
    return run::runSequence(run::loadBagSettings(config, options), options);
  }
  return run::runSequence(run::loadSettings(config), options);
}

TEST(BagRun, SyntheticBagGivesTheFoldersTrajectory) {
  const std::string sequence = test::syntheticSequence("run", 20);
  BagWriteOptions write;
  write.compression = "lz4";
  const std::string bag = test::writeTestBag(sequence, sequence, "sequence.bag", write);
  const run::SequenceRunResult folder = runOn(sequence, test::kTum3, "geometry");
  const run::SequenceRunResult from_bag = runOn(bag, test::kTum3, "geometry");
  ASSERT_EQ(from_bag.trajectory.size(), 20u);
  EXPECT_EQ(trajectoryText(from_bag), trajectoryText(folder));
  ASSERT_TRUE(from_bag.info.source);
  EXPECT_EQ(from_bag.info.source->kind, "bag");
  ASSERT_TRUE(from_bag.info.evaluation);  // groundtruth.txt beside the bag
  EXPECT_EQ(from_bag.info.evaluation->ate_rmse_m, folder.info.evaluation->ate_rmse_m);
}

// The brief's check on real data: TUM fr2/desk's first 50 frames, the full front end.
TEST(BagRun, TumFr2DeskBagGivesTheFoldersTrajectoryByteForByte) {
  AMOS_REQUIRE_DATA("tum_fr2_desk_first50");
  AMOS_REQUIRE_MODELS("nanodet_m_320.onnx");
  const std::string sequence = testing::dataPath("tum_fr2_desk_first50");
  BagWriteOptions write;
  write.compression = "lz4";       // bz2 is covered by bag_reader_test.cc (and takes 5x longer to write)
  write.depth_encoding = "32FC1";  // as the TUM bags
  write.depth_factor = config::loadSettings(test::kTum2).depth_factor;
  const std::string bag = test::writeTestBag(sequence, testing::scratchDirForThisTest("amos_bag_"), "fr2.bag", write);
  const std::string folder = trajectoryText(runOn(sequence, test::kTum2, "full"));
  EXPECT_EQ(trajectoryText(runOn(bag, test::kTum2, "full")), folder);
}

}  // namespace
}  // namespace amos::rosbag
