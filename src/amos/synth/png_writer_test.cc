#include "amos/synth/png_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "amos/core/error.h"
#include "amos/synth/random.h"

namespace amos::synth {
namespace {

TEST(PngWriter, RoundTripsColourGreyAndSixteenBit) {
  const std::filesystem::path dir = std::filesystem::path(AMOS_BINARY_DIR) / "synth_test_output" / "png";
  std::filesystem::create_directories(dir);
  Random rng(1);
  for (int type : {CV_8UC3, CV_8UC1, CV_16UC1}) {
    cv::Mat image(37, 53, type);
    for (int y = 0; y < image.rows; ++y)
      for (int x = 0; x < image.cols * image.channels(); ++x) {
        if (type == CV_16UC1)
          image.ptr<std::uint16_t>(y)[x] = static_cast<std::uint16_t>(rng.bits());
        else
          image.ptr<uchar>(y)[x] = static_cast<uchar>(rng.bits());
      }
    const std::string path = (dir / ("t" + std::to_string(type) + ".png")).string();
    writePng(path, image);
    const cv::Mat back = cv::imread(path, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(back.type(), type);
    EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0) << type;
  }
  EXPECT_THROW(writePng((dir / "bad.png").string(), cv::Mat(4, 4, CV_32F)), core::Error);
  EXPECT_THROW(writePng("/proc/amos_no/bad.png", cv::Mat(4, 4, CV_8UC1, cv::Scalar(0))), core::Error);
}

}  // namespace
}  // namespace amos::synth
