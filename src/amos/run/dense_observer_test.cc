// The observer as a run drives it (onStart, onFrame per frame, onStreamEnd, addToInfo): it writes every file of
// the dense map and the "dense" section of stats.json.
#include "amos/run/dense_observer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>

#include <open3d/geometry/TriangleMesh.h>
#include <open3d/io/TriangleMeshIO.h>

#include "amos/io/occupancy_grid_file.h"
#include "amos/dense/test_room.h"
#include "amos/testing/scratch_dir.h"

namespace amos::run {

using dense::DenseOptions;
using dense::LiveCloud;
namespace {

namespace fs = std::filesystem;

// 5 cm voxels over the whole image: a coarse map of the test room, quick to fuse.
DenseOptions coarseOptions() {
  DenseOptions o;
  o.voxel_size = 0.05;
  o.truncation = 0.15;
  o.scale = 1.0;
  return o;
}

// A rendered room frame as a run hands a tracked frame to its observers (no dynamic mask: mode none).
FrameSnapshot trackedSnapshot(const dense::testing::RoomFrame& f, const core::SE3& T_wc, double timestamp) {
  FrameSnapshot snapshot;
  snapshot.timestamp = timestamp;
  snapshot.state = tracking::TrackingState::kOk;
  snapshot.T_cw = T_wc.inverse();
  snapshot.frame.depth = f.depth;
  snapshot.frame.bgr = f.bgr;
  return snapshot;
}

TEST(DenseObserver, WritesEveryFileOfTheDenseMap) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_dense_observer_");
  DenseOptions o = coarseOptions();
  o.mask_margin_px = 2;
  std::size_t last_cloud_frames = 0;
  DenseObserver observer(o, dir.string(), [&](const LiveCloud& cloud) { last_cloud_frames = cloud.frames_fused; });
  RunStart start;
  start.camera = dense::testing::roomCamera();
  observer.onStart(start);
  std::vector<io::StampedPose> trajectory;
  const std::vector<dense::testing::Box> boxes = {{{1.0, -0.3, 0}, {1.4, 0.3, 0.8}, true}};
  for (int i = 0; i < 16; ++i) {
    const core::SE3 T_wc = dense::testing::cameraPose({0, 0, 1.3}, 2 * M_PI * i / 16, -0.4);
    const dense::testing::RoomFrame f = dense::testing::renderRoom(start.camera, T_wc, boxes);
    FrameSnapshot snapshot = trackedSnapshot(f, T_wc, 10 + i * 0.1);
    if (i == 5) snapshot.state = tracking::TrackingState::kLost;
    snapshot.dynamic_mask = f.mask;
    observer.onFrame(snapshot);
    if (i != 5) trajectory.push_back({snapshot.timestamp, T_wc});
  }
  observer.onStreamEnd();
  report::RunInfo info;
  const report::OptionalStage stage = observer.finishMap(trajectory, info);
  EXPECT_EQ(stage.status, report::OptionalStage::Status::kDone) << stage.reason;
  for (const std::string& name : DenseObserver::outputNames()) EXPECT_TRUE(fs::exists(dir / name)) << name;
  ASSERT_TRUE(info.sections.contains("dense"));
  EXPECT_EQ(info.sections["dense"]["frames_fused"].get<int>(), 15);  // the lost frame is not fused
  EXPECT_EQ(last_cloud_frames, 15u) << "the last cloud handed to the viewer is the final map's";
  EXPECT_GT(info.sections["dense"]["removed_points"].get<int>(), 0);
  open3d::geometry::TriangleMesh mesh;
  ASSERT_TRUE(open3d::io::ReadTriangleMesh((dir / "mesh.ply").string(), mesh));
  EXPECT_GT(mesh.triangles_.size(), 1000u);
  EXPECT_TRUE(mesh.HasVertexColors());
  EXPECT_NO_THROW(io::readOccupancyGridFile((dir / "occupancy.yaml").string()));
  fs::remove_all(dir);
}

TEST(DenseObserver, WritesAnEmptyRemovedCloudWhenNothingWasDynamic) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_dense_observer_");
  DenseObserver observer(coarseOptions(), dir.string());
  RunStart start;
  start.camera = dense::testing::roomCamera();
  observer.onStart(start);
  std::vector<io::StampedPose> trajectory;
  for (int i = 0; i < 4; ++i) {
    const core::SE3 T_wc = dense::testing::cameraPose({0, 0, 1.3}, 0.5 * i, -0.4);
    const FrameSnapshot snapshot = trackedSnapshot(dense::testing::renderRoom(start.camera, T_wc, {}), T_wc, i);
    observer.onFrame(snapshot);
    trajectory.push_back({snapshot.timestamp, T_wc});
  }
  observer.onStreamEnd();
  report::RunInfo info;
  observer.finishMap(trajectory, info);
  // A valid PLY without vertices (Open3D neither writes nor reads one, so its header is checked).
  std::ifstream removed(dir / "removed_points.ply");
  const std::string text((std::istreambuf_iterator<char>(removed)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.rfind("ply\nformat binary_little_endian 1.0\nelement vertex 0\n", 0), 0u) << text;
  EXPECT_EQ(info.sections["dense"]["removed_points"].get<int>(), 0);
  fs::remove_all(dir);
}

// The room seen from a turning camera (16 frames), fed to `observer`; returns the trajectory.
std::vector<io::StampedPose> feedRoom(DenseObserver& observer) {
  RunStart start;
  start.camera = dense::testing::roomCamera();
  observer.onStart(start);
  std::vector<io::StampedPose> trajectory;
  for (int i = 0; i < 16; ++i) {
    const core::SE3 T_wc = dense::testing::cameraPose({0, 0, 1.3}, 2 * M_PI * i / 16, -0.4);
    const FrameSnapshot snapshot =
        trackedSnapshot(dense::testing::renderRoom(start.camera, T_wc, {}), T_wc, 10 + i * 0.1);
    observer.onFrame(snapshot);
    trajectory.push_back({snapshot.timestamp, T_wc});
  }
  observer.onStreamEnd();
  return trajectory;
}

TEST(DenseObserver, AFloorPlanThatCannotBeWrittenLeavesTheOtherFilesAndSaysWhy) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_dense_observer_");
  fs::create_directories(dir / "occupancy.pgm");  // in the way of the floor plan's image
  DenseObserver observer(coarseOptions(), dir.string());
  report::RunInfo info;
  const report::OptionalStage stage = observer.finishMap(feedRoom(observer), info);
  EXPECT_EQ(stage.status, report::OptionalStage::Status::kFailed);
  EXPECT_NE(stage.reason.find("occupancy.yaml"), std::string::npos) << stage.reason;
  for (const char* name : {"mesh.ply", "cloud.ply", "removed_points.ply"}) {
    EXPECT_TRUE(fs::is_regular_file(dir / name)) << name;
    EXPECT_EQ(info.sections["dense"]["files"][name], "written") << name;
  }
  EXPECT_EQ(info.sections["dense"]["files"]["occupancy.yaml"].get<std::string>().rfind("failed: ", 0), 0u);
  EXPECT_GT(info.sections["dense"]["mesh"]["vertices"].get<int>(), 0);
  fs::remove_all(dir);
}

TEST(DenseObserver, AStopDuringTheFinalFusionWritesNoDenseFile) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_dense_observer_");
  DenseObserver observer(coarseOptions(), dir.string());
  report::RunInfo info;
  const std::atomic<bool> stop{true};
  const report::OptionalStage stage = observer.finishMap(feedRoom(observer), info, &stop);
  EXPECT_EQ(stage.status, report::OptionalStage::Status::kInterrupted);
  EXPECT_FALSE(fs::exists(dir / "mesh.ply"));
  EXPECT_FALSE(info.sections.contains("dense"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace amos::run
