// PacedFeeder: frames reach stage A while stage B works on the previous one, in order, until the source ends; a
// source error reaches the loop.
#include "amos/run/paced_feeder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>

#include "amos/config/settings.h"
#include "amos/config/slam_options.h"
#include "amos/core/error.h"
#include "amos/io/dataset.h"
#include "amos/run/sequence_run.h"
#include "amos/testing/shared_data.h"
#include "amos/testing/test_inputs.h"

namespace amos::run {
namespace {

using amos::testing::kFr2Data;
using amos::testing::kFr2;
using amos::testing::kTum2;

// Hands out preloaded frames at once (a camera that is always ahead), then ends or fails.
class ListSource : public io::FrameSource {
 public:
  ListSource(std::vector<io::RgbdFrame> frames, bool fail_at_end) : frames_(std::move(frames)), fail_(fail_at_end) {}
  std::optional<io::RgbdFrame> next() override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (i_ < frames_.size()) return frames_[i_++];
    if (fail_) throw core::Error("device unplugged");
    return std::nullopt;
  }
  std::optional<io::RgbdFrame> poll() override { return next(); }
  std::size_t size() const override { return frames_.size(); }
  io::SourceStats stats() const override { return {}; }

 private:
  std::mutex mutex_;
  std::vector<io::RgbdFrame> frames_;
  std::size_t i_ = 0;
  bool fail_;
};

std::vector<io::RgbdFrame> fr2Frames(std::size_t count) {
  io::SequenceIndex index = io::indexSequence(kFr2);
  index.frames.resize(count);
  io::SequenceReader reader(std::move(index), io::ReaderOptions{});
  std::vector<io::RgbdFrame> frames;
  while (auto f = reader.next()) frames.push_back(std::move(*f));
  return frames;
}

struct Fed {
  std::vector<std::size_t> indices;  // processed frames' indices, in order
  std::size_t ahead = 0;             // times the next frame was already in stage A when a frame's stage B ended
};

Fed feed(io::FrameSource& source) {
  const config::Settings settings = config::loadSettings(kTum2);
  system::SlamSystem slam(config::slamOptionsFromSettings(settings, true));
  dynamic::DynamicOptions options = settings.dynamic;
  options.mode = dynamic::DynamicMode::kGeometry;
  system::DynamicPipeline pipeline(slam, options, nullptr);
  Fed fed;
  {
    PacedFeeder feeder(source, pipeline);
    while (feeder.nextForStageB()) {
      fed.indices.push_back(pipeline.processNext().frame.index);
      fed.ahead += pipeline.waiting() > 0;
    }
  }
  pipeline.finish();
  return fed;
}

TEST(PacedFeeder, StageAOfTheNextFrameRunsBesideStageB) {
  AMOS_REQUIRE_DATA(kFr2Data);
  ListSource source(fr2Frames(8), false);
  const Fed fed = feed(source);
  EXPECT_EQ(fed.indices, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  // Stage B of a frame takes milliseconds, a push microseconds: the next frame is nearly always there already.
  EXPECT_GE(fed.ahead, 5u);
}

TEST(PacedFeeder, ASourceErrorEndsTheLoopWithTheError) {
  AMOS_REQUIRE_DATA(kFr2Data);
  ListSource source(fr2Frames(3), true);
  EXPECT_THROW(feed(source), core::Error);
}

}  // namespace
}  // namespace amos::run
