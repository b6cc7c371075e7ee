// A bag written from a folder reads back as the folder: the same frames (stamps, colour, depth), whatever the
// compression and the encodings, paired by stamp as the folder's lists are.
#include "amos/rosbag/bag_reader.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <tuple>

#include "amos/rosbag/bag_index.h"
#include "amos/rosbag/test_bags.h"

namespace amos::rosbag {
namespace {

bool sameMat(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() &&
         (a.empty() || cv::norm(a, b, cv::NORM_INF) == 0.0);
}

using Encodings = std::tuple<std::string, std::string, std::string>;  // compression, colour, depth

class BagReadsAsItsFolder : public ::testing::TestWithParam<Encodings> {};

TEST_P(BagReadsAsItsFolder, SameFramesAsTheFolderReader) {
  const auto& [compression, colour, depth] = GetParam();
  const std::string sequence = test::syntheticSequence("reader", 4);
  BagWriteOptions write;
  write.compression = compression;
  write.colour_encoding = colour;
  write.depth_encoding = depth;
  const std::string bag =
      test::writeTestBag(sequence, testing::scratchDirForThisTest("amos_bag_"), "frames.bag", write);

  const io::SequenceIndex folder = io::indexSequence(sequence);
  const BagIndex index = indexBag(bag);
  EXPECT_EQ(index.topics.rgb, "/camera/rgb/image_color");
  EXPECT_EQ(index.topics.camera_info, "/camera/rgb/camera_info");
  ASSERT_TRUE(index.camera_info);
  EXPECT_EQ(index.camera_info->fx, test::syntheticCamera().fx);
  ASSERT_EQ(index.sequence.frames.size(), folder.frames.size());
  EXPECT_EQ(index.sequence.groundtruth_file, "");  // none beside the bag

  io::ReaderOptions options;
  io::SequenceReader from_folder(folder, options);
  const auto from_bag = openBagReader(index, options);
  EXPECT_EQ(from_bag->size(), folder.frames.size());
  for (std::size_t i = 0; i < folder.frames.size(); ++i) {
    const auto expected = from_folder.next();
    const auto got = from_bag->next();
    ASSERT_TRUE(expected && got) << "frame " << i;
    EXPECT_EQ(got->timestamp, expected->timestamp) << "frame " << i;  // the same double, not a close one
    EXPECT_EQ(got->index, expected->index);
    EXPECT_TRUE(sameMat(got->bgr, expected->bgr)) << "frame " << i;
    EXPECT_TRUE(sameMat(got->depth, expected->depth)) << "frame " << i;
  }
  EXPECT_FALSE(from_bag->next());
  EXPECT_EQ(from_bag->stats().delivered, folder.frames.size());
}

INSTANTIATE_TEST_SUITE_P(CompressionsAndEncodings, BagReadsAsItsFolder,
                         ::testing::Values(Encodings{"none", "rgb8", "16UC1"}, Encodings{"bz2", "bgr8", "32FC1"},
                                           Encodings{"lz4", "rgb8", "16UC1"}),
                         [](const auto& info) {
                           return std::get<0>(info.param) + "_" + std::get<1>(info.param) + "_" +
                                  std::get<2>(info.param);
                         });

TEST(BagSource, FirstFrameAndMaxFramesSelectTheSameFramesAsTheFolder) {
  const std::string sequence = test::syntheticSequence("reader", 4);
  const std::string bag = test::writeTestBag(sequence, testing::scratchDirForThisTest("amos_bag_"), "frames.bag");
  BagIndex index = indexBag(bag);
  selectFrames(index, 1, 2);
  ASSERT_EQ(index.sequence.frames.size(), 2u);
  const io::SequenceIndex folder = io::indexSequence(sequence);
  EXPECT_EQ(index.sequence.frames[0].t_rgb, folder.frames[1].t_rgb);
  const auto reader = openBagReader(index, io::ReaderOptions{});
  const auto first = reader->next();
  ASSERT_TRUE(first);
  EXPECT_EQ(first->timestamp, folder.frames[1].t_rgb);
  EXPECT_EQ(first->index, 0u);
}

TEST(BagSource, GroundTruthBesideTheBagIsTheSequences) {
  const std::string sequence = test::syntheticSequence("reader", 4);
  const std::string bag = test::writeTestBag(sequence, sequence, "beside.bag");
  EXPECT_EQ(indexBag(bag).sequence.groundtruth_file, sequence + "/groundtruth.txt");
}

}  // namespace
}  // namespace amos::rosbag
