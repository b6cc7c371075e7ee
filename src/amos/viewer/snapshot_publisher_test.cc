#include "amos/viewer/snapshot_publisher.h"

#include <gtest/gtest.h>

#include <memory>
#include <thread>

#include "amos/core/error.h"

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

// The live dense cloud: handed over from another thread while frames go, it reaches the live state thinned to
// the limit; before the run starts and after it ends it is published at once; wrong sizes are refused.
TEST(SnapshotPublisher, PublishesTheLiveDenseCloudThinned) {
  LiveState state;
  PublisherOptions options;
  options.frame_period = std::chrono::milliseconds(0);
  options.dense_period = std::chrono::milliseconds(0);
  options.dense_max_points = 100;
  SnapshotPublisher publisher(state, options);
  publisher.publishDenseCloud({0, 0, 1}, {1, 2, 3});  // before onStart: at once
  EXPECT_EQ(state.stateJson()["dense"]["live"]["vertices"], 1);
  run::RunStart start;
  start.map = std::make_shared<map::Map>();
  publisher.onStart(start);
  std::thread fusion([&] {
    std::vector<float> xyz(3 * 1000, 0.5f);
    std::vector<std::uint8_t> rgb(3 * 1000, 128);
    publisher.publishDenseCloud(std::move(xyz), std::move(rgb));
  });
  fusion.join();
  run::FrameSnapshot f;
  f.processed = 1;
  publisher.onFrame(f);
  publisher.onEnd({}, report::RunInfo{});
  EXPECT_EQ(state.stateJson()["dense"]["live"]["vertices"], 100);
  publisher.publishDenseCloud(std::vector<float>(3 * 7, 1.0f), std::vector<std::uint8_t>(3 * 7, 9));  // after onEnd
  EXPECT_EQ(state.stateJson()["dense"]["live"]["vertices"], 7);
  EXPECT_THROW(publisher.publishDenseCloud({0, 0, 1}, {1, 2}), core::Error);
}

}  // namespace
}  // namespace amos::viewer
