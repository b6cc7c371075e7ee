#include "amos/viewer/snapshot_publisher.h"

#include <gtest/gtest.h>

#include <memory>

#include "amos/report/run_report.h"

namespace amos::viewer {
namespace {

// The viewer's observer driven alone with synthetic frames (no run): the frames' poses reach the live state, and
// onEnd publishes the final trajectory and the summary.
TEST(SnapshotPublisher, PublishesTheFramesAndTheEnd) {
  LiveState state;
  SnapshotPublisher publisher(state, {std::chrono::milliseconds(0), std::chrono::milliseconds(0),
                                      std::chrono::milliseconds(0), 64});
  run::RunStart start;
  start.map = std::make_shared<map::Map>();
  start.total_frames = 5;
  start.sequence = "synthetic";
  start.mode = "none";
  publisher.onStart(start);
  std::vector<io::StampedPose> trajectory;
  for (std::size_t i = 0; i < 5; ++i) {
    run::FrameSnapshot f;
    f.index = i;
    f.total = 5;
    f.processed = i + 1;
    f.timestamp = 1.0 + 0.1 * i;
    f.state = tracking::TrackingState::kOk;
    f.T_cw.translation() = Eigen::Vector3d(-0.1 * i, 0, 0);
    f.bgr = cv::Mat(48, 64, CV_8UC3, cv::Scalar(40, 90, 160));
    publisher.onFrame(f);
    trajectory.push_back({f.timestamp, f.T_cw.inverse()});
  }
  report::RunInfo info;
  info.wall_time_s = 1.5;
  publisher.onEnd(trajectory, info);
  const nlohmann::json s = state.stateJson();
  EXPECT_EQ(s["trajectory"].size(), 5u) << s.dump();
  EXPECT_EQ(s["summary"]["end"], "complete") << s.dump();
  EXPECT_EQ(s["summary"]["frames"], 5) << s.dump();
}

}  // namespace
}  // namespace amos::viewer
