#include "amos/report/mask_outputs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "amos/core/error.h"
#include "amos/testing/scratch_dir.h"

namespace amos::report {
namespace {

namespace fs = std::filesystem;

TEST(MaskOutputs, EvenlySpacedFramesAreSliceMiddles) {
  EXPECT_EQ(evenlySpacedFrames(80, 8), (std::vector<std::size_t>{5, 15, 25, 35, 45, 55, 65, 75}));
  EXPECT_EQ(evenlySpacedFrames(3, 8), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(evenlySpacedFrames(10, 1), (std::vector<std::size_t>{5}));
  EXPECT_TRUE(evenlySpacedFrames(0, 8).empty());
  const auto many = evenlySpacedFrames(301, 8);
  ASSERT_EQ(many.size(), 8u);
  for (std::size_t i = 1; i < many.size(); ++i) EXPECT_GT(many[i], many[i - 1]);
  EXPECT_LT(many.back(), 301u);
}

TEST(MaskOutputs, OverlayTintsTheDynamicMaskAndOutlinesTheOthers) {
  const cv::Mat grey(120, 160, CV_8UC3, cv::Scalar(100, 100, 100));
  cv::Mat dynamic(grey.size(), CV_8U, cv::Scalar(0)), prior = dynamic.clone(), truth = dynamic.clone();
  dynamic(cv::Rect(20, 30, 40, 40)).setTo(255);
  prior(cv::Rect(90, 30, 40, 40)).setTo(255);
  truth(cv::Rect(20, 30, 40, 40)).setTo(255);
  const cv::Mat out = renderMaskOverlay(grey, dynamic, prior, truth, "");
  ASSERT_EQ(out.size(), grey.size());
  // Inside the dynamic square: half grey, half red.
  EXPECT_EQ(out.at<cv::Vec3b>(50, 40), cv::Vec3b(50, 50, 178));
  // Inside the prior square: untouched; on its border: yellow.
  EXPECT_EQ(out.at<cv::Vec3b>(50, 110), cv::Vec3b(100, 100, 100));
  EXPECT_EQ(out.at<cv::Vec3b>(50, 90), cv::Vec3b(0, 230, 255));
  // On the truth square's border: green.
  EXPECT_EQ(out.at<cv::Vec3b>(50, 20), cv::Vec3b(0, 220, 0));
  // Away from everything: untouched.
  EXPECT_EQ(out.at<cv::Vec3b>(50, 75), cv::Vec3b(100, 100, 100));
  EXPECT_THROW(renderMaskOverlay(grey, cv::Mat(10, 10, CV_8U), cv::Mat(), cv::Mat(), ""), core::Error);
}

TEST(MaskOutputs, WriterWritesEveryMaskAndTheChosenOverlays) {
  const fs::path dir = testing::scratchDir("mask_outputs_writer") / "out";
  MaskOutputWriter writer(dir.string(), 20, 4);
  const cv::Mat bgr(48, 64, CV_8UC3, cv::Scalar(10, 20, 30));
  cv::Mat dynamic(bgr.size(), CV_8U, cv::Scalar(0));
  dynamic(cv::Rect(0, 0, 8, 8)).setTo(1);  // any non-zero value is dynamic
  for (std::size_t k = 0; k < 20; ++k) {
    const std::string rgb = "/somewhere/rgb/1700000000." + std::to_string(100 + k) + ".png";
    writer.add(k, rgb, bgr, k == 0 ? cv::Mat() : dynamic, cv::Mat(), cv::Mat());
  }
  EXPECT_EQ(writer.masksWritten(), 20u);
  EXPECT_EQ(writer.overlaysWritten(), 4u);
  const cv::Mat first = cv::imread((dir / "masks" / "1700000000.100.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(first), 0);  // no mask (mode none) = all static
  const cv::Mat later = cv::imread((dir / "masks" / "1700000000.119.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(later.empty());
  EXPECT_EQ(cv::countNonZero(later), 64);
  EXPECT_EQ(later.at<uchar>(0, 0), 255);
  // Overlays of frames 2, 7, 12, 17.
  for (int k : {2, 7, 12, 17})
    EXPECT_TRUE(fs::exists(dir / "overlays" / ("1700000000." + std::to_string(100 + k) + ".png"))) << k;
  std::size_t overlays = 0;
  for (const auto& entry : fs::directory_iterator(dir / "overlays")) overlays += entry.is_regular_file();
  EXPECT_EQ(overlays, 4u);
}

}  // namespace
}  // namespace amos::report
