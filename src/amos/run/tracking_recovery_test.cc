// Tracking recovery after a loss (Tracking.recoveryFrames), end to end on real frames: the view is blanked for a
// few frames (as when a person walks right in front of the camera), then the camera sees the scene again near
// where it was. The global relocaliser is switched off here (Relocalization.minInliers out of reach), so only the
// recovery search around the last tracked pose can bring tracking back.
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "amos/config/settings.h"
#include "amos/config/slam_options.h"
#include "amos/io/dataset.h"
#include "amos/run/sequence_run.h"
#include "amos/system/slam_system.h"
#include "amos/testing/shared_data.h"
#include "amos/testing/slam_input.h"
#include "amos/testing/test_inputs.h"

namespace amos::run {
namespace {

using amos::testing::kFr2Data;
using amos::testing::kFr2;
using amos::testing::kTum2;

std::vector<io::RgbdFrame> loadFrames(const config::Settings& settings, std::size_t count) {
  io::SequenceReader reader(io::indexSequence(kFr2), settings.readerOptions());
  std::vector<io::RgbdFrame> frames;
  while (frames.size() < count) {
    std::optional<io::RgbdFrame> f = reader.next();
    if (!f) break;
    frames.push_back(std::move(*f));
  }
  return frames;
}

struct RecoveryRun {
  std::vector<tracking::TrackingState> states;
  std::vector<core::SE3> T_cw;
};

// Frames [blank_from, blank_to) are black (no features: tracking is lost there).
RecoveryRun run(const config::Settings& settings, const std::vector<io::RgbdFrame>& frames, int recovery_frames,
                std::size_t blank_from, std::size_t blank_to) {
  system::SlamOptions options = config::slamOptionsFromSettings(settings, /*deterministic=*/true);
  options.tracking.recovery_frames = recovery_frames;
  options.tracking.relocalization.min_inliers = 1000000;  // the global relocaliser never accepts a pose
  system::SlamSystem slam(options);
  const feature::OrbExtractor orb(options.orb);
  RecoveryRun out;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    io::RgbdFrame frame = frames[i];
    if (i >= blank_from && i < blank_to) frame.bgr = cv::Mat::zeros(frame.bgr.size(), frame.bgr.type());
    const system::FrameOutput o = slam.track(amos::testing::trackInput(orb, frame));
    out.states.push_back(o.track.state);
    out.T_cw.push_back(o.track.T_cw);
  }
  slam.finish();
  return out;
}

TEST(TrackingRecovery, LostFramesRecoverNearTheLastPoseWithoutTheRelocaliser) {
  AMOS_REQUIRE_DATA(kFr2Data);
  const config::Settings settings = config::loadSettings(kTum2);
  const std::vector<io::RgbdFrame> frames = loadFrames(settings, 16);
  ASSERT_EQ(frames.size(), 16u);
  const RecoveryRun reference = run(settings, frames, 30, 0, 0);
  const RecoveryRun with_recovery = run(settings, frames, 30, 10, 13);
  const RecoveryRun without = run(settings, frames, 0, 10, 13);
  for (std::size_t i = 10; i < 13; ++i) {
    EXPECT_EQ(with_recovery.states[i], tracking::TrackingState::kLost) << "blank frame " << i;
    EXPECT_EQ(without.states[i], tracking::TrackingState::kLost) << "blank frame " << i;
  }
  // The first real frame after the blank ones is tracked again, where the undisturbed run put it.
  for (std::size_t i = 13; i < 16; ++i) {
    ASSERT_EQ(with_recovery.states[i], tracking::TrackingState::kOk) << "frame " << i;
    const core::SE3 diff = with_recovery.T_cw[i] * reference.T_cw[i].inverse();
    EXPECT_LT(diff.translation().norm(), 0.02) << "frame " << i;
  }
  // Without the recovery search (and without the relocaliser) it stays lost: the test can fail.
  EXPECT_EQ(without.states[13], tracking::TrackingState::kLost);
}

}  // namespace
}  // namespace amos::run
