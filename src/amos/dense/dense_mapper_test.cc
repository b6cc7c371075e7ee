// Fusion on a known scene (test_room.h): the static room comes out within a voxel, a masked mover leaves no surface
// while an unmasked one leaves a ghost, the floor and the live cloud are found.
#include "amos/dense/dense_mapper.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>

#include "amos/core/stage_timer.h"
#include "amos/core/option_error.h"
#include "amos/dense/test_room.h"

namespace amos::dense {
namespace {

using testing::Box;

DenseOptions roomOptions() {
  DenseOptions o;
  o.voxel_size = 0.05;
  o.truncation = 0.15;
  o.scale = 1.0;
  o.min_depth = 0.1;
  o.max_depth = 6.0;
  o.mask_margin_px = 2;
  o.edge_margin_px = 1;
  o.live_every = 2;
  o.live_period_s = 0.001;
  return o;
}

// The camera turns once round the room's middle, looking slightly down; a mover, when asked for, walks 1.2 m in
// front of it (always in view: what smears a person into a map that does not leave it out).
struct Sweep {
  std::vector<Box> static_boxes;
  bool with_mover = false;
  bool mask_mover = true;
  int frames = 24;
};

DenseMap fuse(const Sweep& sweep, const DenseOptions& options, LiveCloudCallback live = {}) {
  const core::CameraIntrinsics k = testing::roomCamera();
  DenseMapper mapper(options, k, std::move(live));
  std::vector<io::StampedPose> trajectory;
  for (int i = 0; i < sweep.frames; ++i) {
    const double yaw = 2 * M_PI * i / sweep.frames;
    const core::SE3 T_wc = testing::cameraPose({0.1, -0.2, 1.3}, yaw, -0.35);
    std::vector<Box> boxes = sweep.static_boxes;
    if (sweep.with_mover) {
      const Eigen::Vector3d at = T_wc.translation() + 1.2 * Eigen::Vector3d(std::cos(yaw), std::sin(yaw), 0);
      boxes.push_back({at + Eigen::Vector3d(-0.2, -0.2, -1.3), at + Eigen::Vector3d(0.2, 0.2, 0.4), true});
    }
    const testing::RoomFrame f = testing::renderRoom(k, T_wc, boxes);
    const double stamp = 100 + i / 30.0;
    EXPECT_TRUE(mapper.push({stamp, T_wc.inverse(), {f.depth, f.bgr, sweep.mask_mover ? f.mask : cv::Mat()}}));
    trajectory.push_back({stamp, T_wc});
  }
  mapper.finish();
  return mapper.fuseFinal(trajectory);
}

std::vector<double> distancesToStatic(const DenseMap& map, const std::vector<Box>& boxes) {
  std::vector<double> out;
  for (const auto& v : map.mesh.vertices) out.push_back(testing::distanceToStatic(v, boxes));
  return out;
}

std::size_t ghosts(const std::vector<double>& distances, double tolerance) {
  return static_cast<std::size_t>(std::count_if(distances.begin(), distances.end(), [&](double d) { return d > tolerance; }));
}

TEST(DenseMapper, FusesAKnownRoomWithinAVoxel) {
  const DenseOptions o = roomOptions();
  const DenseMap map = fuse({}, o);
  ASSERT_GT(map.mesh.vertices.size(), 5000u);
  const std::vector<double> d = distancesToStatic(map, {});
  EXPECT_LT(core::percentile(d, 0.5), 0.3 * o.voxel_size);
  EXPECT_LT(core::percentile(d, 0.95), 1.0 * o.voxel_size);
  EXPECT_EQ(map.stats["frames_fused"].get<int>(), 24);
  EXPECT_EQ(map.stats["frames_dropped"].get<int>(), 0);
  EXPECT_EQ(map.mesh.colours.size(), map.mesh.vertices.size());
  EXPECT_GT(map.cloud.points.size(), 1000u);
  EXPECT_TRUE(map.removed.points.empty());  // nothing was marked dynamic
}

TEST(DenseMapper, FindsTheFloorOfTheRoom) {
  const DenseMap map = fuse({}, roomOptions());
  ASSERT_TRUE(map.floor.has_value());
  EXPECT_GT(map.floor->normal.z(), 0.999);
  EXPECT_NEAR(map.floor->offset, 0.0, 0.03);
  EXPECT_NEAR(map.floor->camera_height, 1.3, 0.03);
  ASSERT_TRUE(map.grid.has_value());
  EXPECT_GT(map.grid->count(kFreeCell), 0);
  EXPECT_GT(map.grid->count(kOccupiedCell), 0);  // the walls
}

TEST(DenseMapper, AMaskedMoverLeavesNoSurfaceAndAnUnmaskedOneAGhost) {
  DenseOptions o = roomOptions();
  o.carve = false;  // the fusion alone; carving: the test below
  Sweep masked;
  masked.with_mover = true;
  Sweep unmasked = masked;
  unmasked.mask_mover = false;
  const DenseMap clean = fuse(masked, o), smeared = fuse(unmasked, o);
  const double tolerance = 2 * o.voxel_size;
  const std::size_t ghosts_masked = ghosts(distancesToStatic(clean, {}), tolerance);
  const std::size_t ghosts_unmasked = ghosts(distancesToStatic(smeared, {}), tolerance);
  EXPECT_GT(ghosts_unmasked, 500u);
  EXPECT_LT(ghosts_masked, ghosts_unmasked / 100 + 5);
  EXPECT_GT(clean.removed.points.size(), 100u);  // what was left out, back-projected
  EXPECT_TRUE(smeared.removed.points.empty());
}

// A person the mask misses while standing for the first 6 frames, then gone; the camera pans to and fro.
DenseMap fuseAStandingGhost(const DenseOptions& options) {
  const core::CameraIntrinsics k = testing::roomCamera();
  DenseMapper mapper(options, k);
  std::vector<io::StampedPose> trajectory;
  const Box person{{0.6, -0.5, 0.0}, {0.9, -0.1, 1.8}, true};
  for (int i = 0; i < 24; ++i) {
    const core::SE3 T_wc = testing::cameraPose({-1.0, -0.2, 1.3}, 0.5 * std::sin(2 * M_PI * i / 12), -0.3);
    const testing::RoomFrame f = testing::renderRoom(k, T_wc, i < 6 ? std::vector<Box>{person} : std::vector<Box>{});
    const double stamp = 100 + i / 30.0;
    EXPECT_TRUE(mapper.push({stamp, T_wc.inverse(), {f.depth, f.bgr, cv::Mat()}}));  // no mask: missed
    trajectory.push_back({stamp, T_wc});
  }
  mapper.finish();
  return mapper.fuseFinal(trajectory);
}

TEST(DenseMapper, CarvesTheGhostOfAMissedPersonThatLaterFramesSeeThrough) {
  DenseOptions o = roomOptions();
  o.carve = false;
  const DenseMap kept = fuseAStandingGhost(o);
  o.carve = true;
  const DenseMap carved = fuseAStandingGhost(o);
  const double tolerance = 2 * o.voxel_size;
  const std::size_t ghosts_kept = ghosts(distancesToStatic(kept, {}), tolerance);
  const std::size_t ghosts_carved = ghosts(distancesToStatic(carved, {}), tolerance);
  EXPECT_GT(ghosts_kept, 150u);
  EXPECT_LT(ghosts_carved, ghosts_kept / 20 + 5) << ghosts_carved << " of " << ghosts_kept << " ghost vertices remain";
  EXPECT_GT(carved.stats["carving"]["vertices_carved"].get<int>(), 0);
  EXPECT_GE(carved.removed.points.size(), 100u);  // the carved surface joins the removed points
  EXPECT_TRUE(kept.removed.points.empty());
  EXPECT_TRUE(kept.stats["carving"].is_null());
  // The surface cloud and the floor plan follow: nothing stands where the person stood (x 0.6-0.9, y -0.5 to -0.1).
  const auto atThePerson = [](const Eigen::Vector3d& p) {
    return p.x() > 0.55 && p.x() < 0.95 && p.y() > -0.55 && p.y() < -0.05;
  };
  const auto surfaceAtThePerson = [&](const DenseMap& map) {
    return std::count_if(map.cloud.points.begin(), map.cloud.points.end(),
                         [&](const Eigen::Vector3d& p) { return atThePerson(p) && p.z() > 0.2; });
  };
  const auto occupiedAtThePerson = [&](const DenseMap& map) {
    const OccupancyGrid& g = *map.grid;
    int n = 0;
    for (int row = 0; row < g.height; ++row) {
      for (int column = 0; column < g.width; ++column) {
        const Eigen::Vector3d centre_m(g.origin.x() + (column + 0.5) * g.resolution,
                                       g.origin.y() + (g.height - row - 0.5) * g.resolution, 0.0);
        n += g.at(row, column) == kOccupiedCell && atThePerson(g.T_mw.inverse() * centre_m) ? 1 : 0;
      }
    }
    return n;
  };
  ASSERT_TRUE(kept.grid && carved.grid);
  EXPECT_GT(surfaceAtThePerson(kept), 100);
  EXPECT_EQ(surfaceAtThePerson(carved), 0);
  EXPECT_GT(occupiedAtThePerson(kept), 5);
  EXPECT_EQ(occupiedAtThePerson(carved), 0);
}

TEST(DenseMapper, UsesTheFinalTrajectoryNotTheTrackedPoses) {
  // Tracked poses off by 30 cm; the final trajectory is right: the mesh must follow the final one.
  const DenseOptions o = roomOptions();
  const core::CameraIntrinsics k = testing::roomCamera();
  DenseMapper mapper(o, k);
  std::vector<io::StampedPose> trajectory;
  for (int i = 0; i < 12; ++i) {
    const core::SE3 T_wc = testing::cameraPose({0, 0, 1.3}, 2 * M_PI * i / 12, -0.35);
    core::SE3 wrong = T_wc;
    wrong.translation().x() += 0.3;
    const testing::RoomFrame f = testing::renderRoom(k, T_wc, {});
    mapper.push({double(i), wrong.inverse(), {f.depth, f.bgr, f.mask}});
    trajectory.push_back({double(i), T_wc});
  }
  mapper.finish();
  const DenseMap map = mapper.fuseFinal(trajectory);
  EXPECT_LT(core::percentile(distancesToStatic(map, {}), 0.5), 0.3 * o.voxel_size);
}

TEST(DenseMapper, HandsLiveCloudsToItsCallback) {
  std::atomic<int> calls{0};
  std::atomic<std::size_t> points{0};
  fuse({}, roomOptions(), [&](const LiveCloud& cloud) {
    ++calls;
    points = cloud.points.size();
    EXPECT_EQ(cloud.points.size(), cloud.colours.size());
  });
  EXPECT_GT(calls.load(), 0);
  EXPECT_GT(points.load(), 100u);
}

TEST(DenseMapper, WithoutATrajectoryFusesThePosesAsPushedAndKeepsALiveSnapshot) {
  const DenseOptions o = roomOptions();
  const core::CameraIntrinsics k = testing::roomCamera();
  DenseMapper mapper(o, k);  // no callback: the snapshot is there all the same
  EXPECT_EQ(mapper.liveSnapshot(), nullptr);
  for (int i = 0; i < 12; ++i) {
    const core::SE3 T_wc = testing::cameraPose({0, 0, 1.3}, 2 * M_PI * i / 12, -0.35);
    const testing::RoomFrame f = testing::renderRoom(k, T_wc, {});
    mapper.push({double(i), T_wc.inverse(), {f.depth, f.bgr, f.mask}});
  }
  mapper.finish();
  const auto snapshot = mapper.liveSnapshot();
  ASSERT_NE(snapshot, nullptr);
  EXPECT_GT(snapshot->points.size(), 100u);
  const DenseMap map = mapper.fuseFinal();
  EXPECT_EQ(map.stats["frames_fused"].get<int>(), 12);
  EXPECT_LT(core::percentile(distancesToStatic(map, {}), 0.5), 0.3 * o.voxel_size);
}

TEST(DenseMapper, AStopFlagAbandonsTheFinalFusion) {
  const core::CameraIntrinsics k = testing::roomCamera();
  DenseMapper mapper(roomOptions(), k);
  const core::SE3 T_wc = testing::cameraPose({0, 0, 1.3}, 0, -0.35);
  const testing::RoomFrame f = testing::renderRoom(k, T_wc, {});
  mapper.push({0.0, T_wc.inverse(), {f.depth, f.bgr, f.mask}});
  mapper.finish();
  const std::atomic<bool> stop{true};
  EXPECT_THROW(mapper.fuseFinal(&stop), FusionStopped);
}

TEST(DenseMapper, KeepsEveryFrameStepthFrame) {
  DenseOptions o = roomOptions();
  o.frame_step = 3;
  const DenseMap map = fuse({}, o);
  EXPECT_EQ(map.stats["frames_kept"].get<int>(), 8);
  EXPECT_EQ(map.stats["frames_tracked"].get<int>(), 24);
}

TEST(DenseMapper, RefusesBadOptionsNamingTheMember) {
  DenseOptions o = roomOptions();
  o.truncation = o.voxel_size;
  try {
    DenseMapper mapper(o, testing::roomCamera());
    FAIL() << "accepted a truncation below 2 voxels";
  } catch (const core::InvalidOption& e) {
    EXPECT_NE(std::string(e.what()).find("truncation"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace amos::dense
