#include "amos/run/mask_writing.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>

#include "amos/run/observer_test_frames.h"

namespace amos::run {
namespace {

namespace fs = std::filesystem;

// Driven alone with a synthetic sequence's frames: one mask per frame named by the RGB stamp (an empty mask is
// written all static), overlays of `overlay_count` frames.
TEST(MaskWriting, WritesEveryMaskAndAFewOverlays) {
  const std::string dir = testing::syntheticSequence("walking_static", 5);
  const fs::path out = fs::path(AMOS_BINARY_DIR) / "test_outputs" / "mask_writing";
  fs::remove_all(out);
  const std::vector<FrameSnapshot> frames = testing::snapshotsOf(dir);
  MaskWriting writing(out.string(), 2, nullptr);
  RunStart start;
  start.total_frames = frames.size();
  writing.onStart(start);
  for (FrameSnapshot f : frames) {
    if (f.index % 2 == 0) {
      f.dynamic_mask = cv::Mat::zeros(f.bgr.size(), CV_8U);
      f.dynamic_mask(cv::Rect(10, 10, 20, 20)).setTo(255);
    }
    writing.onFrame(f);
  }
  EXPECT_EQ(writing.masksWritten(), frames.size());
  EXPECT_EQ(writing.overlaysWritten(), 2u);
  for (const FrameSnapshot& f : frames) {
    const fs::path mask = out / "masks" / fs::path(f.rgb_file).filename();
    ASSERT_TRUE(fs::exists(mask)) << mask;
    const cv::Mat m = cv::imread(mask.string(), cv::IMREAD_UNCHANGED);
    EXPECT_EQ(cv::countNonZero(m), f.index % 2 == 0 ? 400 : 0) << mask;
  }
  std::size_t overlays = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(out / "overlays")) ++overlays;
  EXPECT_EQ(overlays, 2u);
}

}  // namespace
}  // namespace amos::run
