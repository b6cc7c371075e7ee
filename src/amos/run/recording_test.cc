#include "amos/run/recording.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <filesystem>

#include "amos/run/observer_test_frames.h"

namespace amos::run {
namespace {

namespace fs = std::filesystem;

// Driven alone with a synthetic sequence's frames: the recording reads back as a sequence of the same frames, the
// colour bit-identical.
TEST(Recording, WritesTheFramesAsASequence) {
  const std::string dir = testing::syntheticSequence("static_xyz", 3);
  const fs::path out = fs::path(AMOS_BINARY_DIR) / "test_outputs" / "recording";
  fs::remove_all(out);
  const std::vector<FrameSnapshot> frames = testing::snapshotsOf(dir);
  {
    Recording recording(out.string(), 5000.0);
    for (const FrameSnapshot& f : frames) recording.onFrame(f);
    recording.onStreamEnd();
    EXPECT_EQ(recording.framesWritten(), frames.size());
  }
  const std::vector<FrameSnapshot> back = testing::snapshotsOf(out.string());
  ASSERT_EQ(back.size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(back[i].timestamp, frames[i].timestamp);
    EXPECT_EQ(cv::norm(back[i].bgr, frames[i].bgr, cv::NORM_INF), 0.0);
  }
}

}  // namespace
}  // namespace amos::run
