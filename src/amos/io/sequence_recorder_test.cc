#include "amos/io/sequence_recorder.h"

#include <gtest/gtest.h>

#include "amos/testing/scratch_dir.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "amos/core/error.h"
#include "amos/io/dataset.h"

namespace amos::io {
namespace {

namespace fs = std::filesystem;

fs::path freshRecorderDir(const std::string& name) {
  // The recorder makes the folder itself: it must not exist yet.
  const fs::path dir = amos::testing::scratchDir("amos_recorder_test_" + name);
  fs::remove_all(dir);
  return dir;
}

// A frame with random colour and random depth that is a multiple of 1 / factor (as read from a 16-bit PNG), with
// some pixels without depth.
RgbdFrame randomFrame(std::size_t index, double timestamp, double factor, cv::RNG& rng) {
  RgbdFrame f;
  f.index = index;
  f.timestamp = timestamp;
  f.bgr.create(48, 64, CV_8UC3);
  rng.fill(f.bgr, cv::RNG::UNIFORM, 0, 256);
  cv::Mat raw(48, 64, CV_16U);
  rng.fill(raw, cv::RNG::UNIFORM, 0, 65536);
  raw(cv::Rect(0, 0, 8, 8)).setTo(0);
  raw.convertTo(f.depth, CV_32F, 1.0 / factor);  // exactly as loadRgbdFrame converts
  return f;
}

TEST(StampText, SixDecimalsWhenExactElseRoundTrip) {
  EXPECT_EQ(stampText(1548339828.252394), "1548339828.252394");
  EXPECT_EQ(stampText(100.0), "100.000000");
  EXPECT_EQ(stampText(123456789 / 1e6), "123.456789");  // a device's microseconds
  const double awkward = 0.1 + 0.2;                    // needs 17 digits
  EXPECT_EQ(std::strtod(stampText(awkward).c_str(), nullptr), awkward);
  EXPECT_NE(stampText(awkward), "0.300000");
}

// What is recorded reads back through the ordinary sequence reader bit for bit: the same colour, the same depth,
// the same time stamps, in order.
TEST(SequenceRecorder, RecordingReadsBackBitExact) {
  const fs::path dir = freshRecorderDir("bit_exact");
  constexpr double kFactor = 5000.0;
  cv::RNG rng(12);
  const std::vector<double> stamps = {1548339828.252394, 1548339828.285765, 1548339828.317703,
                                     std::nextafter(1548339828.35, 2e9)};  // needs all 17 digits
  std::vector<RgbdFrame> frames;
  {
    SequenceRecorder recorder(dir.string(), kFactor, 2);  // a short queue: add() waits for the writer
    for (std::size_t i = 0; i < stamps.size(); ++i) {
      frames.push_back(randomFrame(i, stamps[i], kFactor, rng));
      recorder.add(frames.back());
    }
    recorder.finish();
    EXPECT_EQ(recorder.framesWritten(), stamps.size());
  }
  const SequenceIndex index = indexSequence(dir.string());
  ASSERT_EQ(index.frames.size(), stamps.size());
  ReaderOptions options;
  options.width = 64;
  options.height = 48;
  options.depth_factor = kFactor;
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    EXPECT_EQ(index.frames[i].t_rgb, stamps[i]);
    EXPECT_EQ(index.frames[i].t_depth, stamps[i]);
    const RgbdFrame back = loadRgbdFrame(index.frames[i], options, i);
    EXPECT_EQ(back.timestamp, stamps[i]);
    ASSERT_EQ(back.bgr.type(), CV_8UC3);
    EXPECT_EQ(cv::norm(back.bgr, frames[i].bgr, cv::NORM_INF), 0.0) << "colour of frame " << i;
    ASSERT_EQ(back.depth.type(), CV_32F);
    EXPECT_EQ(cv::countNonZero(back.depth != frames[i].depth), 0) << "depth of frame " << i;
    EXPECT_EQ(back.depth.at<float>(0, 0), 0.0f);
  }
  EXPECT_TRUE(fs::is_regular_file(dir / "rgb" / "1548339828.252394.png"));
  EXPECT_TRUE(fs::is_regular_file(dir / "depth" / "1548339828.252394.png"));
  fs::remove_all(dir);
}

TEST(SequenceRecorder, InvalidDepthIsWrittenAsNoDepthAndRepeatedStampsAreSkipped) {
  const fs::path dir = freshRecorderDir("invalid_depth");
  RgbdFrame f;
  f.timestamp = 5.0;
  f.bgr = cv::Mat(48, 64, CV_8UC3, cv::Scalar(1, 2, 3));
  f.depth = cv::Mat(48, 64, CV_32F, cv::Scalar(2.0f));
  f.depth.at<float>(0, 0) = std::numeric_limits<float>::quiet_NaN();
  f.depth.at<float>(0, 1) = -1.0f;
  f.depth.at<float>(0, 2) = 20.0f;  // beyond 65535 / 5000 m
  f.depth.at<float>(0, 3) = std::numeric_limits<float>::infinity();
  {
    SequenceRecorder recorder(dir.string(), 5000.0);
    recorder.add(f);
    recorder.add(f);  // same stamp: skipped
    recorder.finish();
    EXPECT_EQ(recorder.framesWritten(), 1u);
  }
  const cv::Mat raw = cv::imread((dir / "depth" / "5.000000.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(raw.type(), CV_16U);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(raw.at<std::uint16_t>(0, c), 0) << "column " << c;
  EXPECT_EQ(raw.at<std::uint16_t>(0, 4), 10000);
  EXPECT_EQ(indexSequence(dir.string()).frames.size(), 1u);
  fs::remove_all(dir);
}

TEST(SequenceRecorder, UnwritableFolderIsAClearError) {
  const fs::path file = freshRecorderDir("not_a_folder");
  std::ofstream(file) << "x";
  try {
    SequenceRecorder recorder(file.string(), 5000.0);
    FAIL() << "expected a core::Error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  fs::remove_all(file);
}

}  // namespace
}  // namespace amos::io
