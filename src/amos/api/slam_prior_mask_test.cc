// The caller's prior mask (issue 52): a synthetic scene whose movers (a pushed box, a rolling chair, a swinging
// door: objects no person network knows) no front-end stage sees in mode none. Masked by the caller from the
// sequence's true mover masks, their keypoints are left out and the trajectory is as good as the one of the run
// whose geometric front end finds them.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cstdio>
#include <filesystem>
#include <optional>

#include "amos/eval/evaluate.h"
#include "amos/eval/ground_truth_masks.h"
#include "amos/io/trajectory.h"
#include "amos/sequence_folder.h"
#include "amos/slam.h"
#include "amos/synth/sequence.h"

namespace amos {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 120;

std::string moversSequence() {
  return synth::cachedSequence((fs::path(AMOS_BINARY_DIR) / "test_outputs" / "api_sequences").string(),
                               "objects_xyz", 1, kFrames);
}

struct Outcome {
  double ate_m = 0;
  std::size_t frames_with_movers = 0;
  std::size_t movers_uncovered = 0;  // pixels of a moving object outside the frame's dynamic mask
  std::size_t removed_on_mover_frames = 0;
};

// Tracks the sequence in `mode`; with `caller_masks` the true mover masks go in as the caller's prior masks.
Outcome trackMovers(Mode mode, bool caller_masks) {
  const std::string dir = moversSequence();
  const std::optional<eval::GroundTruthMasks> truth = eval::GroundTruthMasks::find(dir);
  if (!truth) throw std::runtime_error("the synthetic sequence has no ground-truth masks");
  Options o;
  o.settings_file = std::string(AMOS_SOURCE_DIR) + "/configs/tum3.yaml";
  o.mode = mode;
  o.deterministic = true;
  Slam slam(o);
  SequenceFolder folder(dir);
  Outcome out;
  while (const std::optional<RgbdImages> f = folder.next()) {
    const std::optional<int> k = truth->frameAt(f->timestamp);
    const cv::Mat movers = k ? truth->moverMask(*k) : cv::Mat();
    const bool visible = !movers.empty() && cv::countNonZero(movers) > 0;
    const FrameResult r = slam.track(f->bgr, f->depth, f->timestamp, caller_masks ? movers : cv::Mat());
    if (!visible) continue;
    ++out.frames_with_movers;
    out.movers_uncovered += static_cast<std::size_t>(cv::countNonZero(movers & ~r.dynamic_mask));
    out.removed_on_mover_frames += static_cast<std::size_t>(r.keypoints_removed);
  }
  slam.finish();
  std::vector<io::StampedPose> estimate;
  for (const StampedPose& p : slam.trajectory()) estimate.push_back({p.timestamp, core::SE3(p.T_wc)});
  out.ate_m = eval::evaluate(io::readTumTrajectory(folder.groundTruthFile()), estimate).ate_rmse_m;
  return out;
}

TEST(SlamPriorMask, TheCallersMaskLeavesTheMoversOutAsTheFrontEndDoes) {
  const Outcome plain = trackMovers(Mode::kNone, false);
  const Outcome masked = trackMovers(Mode::kNone, true);
  const Outcome geometry = trackMovers(Mode::kGeometry, false);
  ASSERT_GT(masked.frames_with_movers, 30u);
  EXPECT_EQ(plain.removed_on_mover_frames, 0u);  // mode none alone removes nothing
  EXPECT_EQ(masked.movers_uncovered, 0u);        // every moving pixel is in the dynamic mask
  EXPECT_GT(masked.removed_on_mover_frames, 100u);
  RecordProperty("ate_none_mm", std::to_string(plain.ate_m * 1000));
  RecordProperty("ate_none_caller_mask_mm", std::to_string(masked.ate_m * 1000));
  RecordProperty("ate_geometry_mm", std::to_string(geometry.ate_m * 1000));
  std::printf("ATE: mode none %.2f mm, mode none + caller's mask %.2f mm, mode geometry %.2f mm\n",
              plain.ate_m * 1000, masked.ate_m * 1000, geometry.ate_m * 1000);
  EXPECT_LT(masked.ate_m, geometry.ate_m * 1.25 + 0.0005);
  EXPECT_LT(masked.ate_m, plain.ate_m);
}

}  // namespace
}  // namespace amos
