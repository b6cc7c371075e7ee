// Free-space carving on the ray-cast room (test_room.h) with known answers: a surface fused and then seen through
// goes, a static surface seen at grazing angles or through noisy depth stays; the vote's rules one by one.
#include "amos/dense/free_space_carving.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <open3d/geometry/TriangleMesh.h>

#include "amos/dense/test_room.h"
#include "amos/dense/tsdf_volume.h"

namespace amos::dense {
namespace {

using testing::Box;

DenseOptions carvingRoomOptions() {
  DenseOptions o;
  o.voxel_size = 0.05;
  o.truncation = 0.15;
  o.min_depth = 0.1;
  o.max_depth = 6.0;
  return o;
}

struct View {
  core::SE3 T_wc;
  cv::Mat depth, bgr;
};

View viewOf(const core::SE3& T_wc, const std::vector<Box>& boxes) {
  const testing::RoomFrame f = testing::renderRoom(testing::roomCamera(), T_wc, boxes);
  return {T_wc, f.depth, f.bgr};
}

std::size_t offTheRoom(const std::vector<Eigen::Vector3d>& vertices, double tolerance) {
  std::size_t n = 0;
  for (const auto& v : vertices) n += testing::distanceToStatic(v, {}) > tolerance ? 1 : 0;
  return n;
}

// Fuses every view, votes with every view, carves; returns the mesh's vertices before and after and the result.
struct Carved {
  std::vector<Eigen::Vector3d> before, after;
  CarveResult result;
};

Carved fuseAndCarve(const std::vector<View>& views, const DenseOptions& o) {
  TsdfVolume volume(o);
  const core::CameraIntrinsics k = testing::roomCamera();
  for (const View& v : views) volume.integrate(v.depth, v.bgr, k, v.T_wc.inverse());
  Carved out;
  out.before = volume.extractMesh()->vertices_;
  auto carver = FreeSpaceCarver::ofSurface(volume, seeThroughOptionsOf(o));
  for (const View& v : views) carver.addFrame(v.depth, k, v.T_wc.inverse());
  out.result = carver.carve(volume);
  out.after = volume.extractMesh()->vertices_;
  return out;
}

TEST(FreeSpaceCarving, ASurfaceFusedThenSeenThroughIsRemoved) {
  // A box stands 1 m in front of the east wall for 5 frames (fused: no mask), then is gone for 10 frames.
  const Box box{{0.9, -0.3, 0.0}, {1.1, 0.3, 1.7}, false};
  std::vector<View> views;
  for (int i = 0; i < 15; ++i) {
    const core::SE3 T_wc = testing::cameraPose({-0.5, -0.4 + 0.06 * i, 1.3}, 0.05 * (i % 4) - 0.08, -0.2);
    views.push_back(viewOf(T_wc, i < 5 ? std::vector<Box>{box} : std::vector<Box>{}));
  }
  const DenseOptions o = carvingRoomOptions();
  const Carved c = fuseAndCarve(views, o);
  const double tolerance = 2 * o.voxel_size;
  const std::size_t ghosts_before = offTheRoom(c.before, tolerance), ghosts_after = offTheRoom(c.after, tolerance);
  EXPECT_GT(ghosts_before, 300u);
  EXPECT_LT(ghosts_after, ghosts_before / 20 + 5);
  // The room stays: what was carved is the box, the room's vertices lose at most a ring around its shadow.
  EXPECT_GT(c.after.size() - ghosts_after, (c.before.size() - ghosts_before) * 95 / 100);
  EXPECT_GT(c.result.voxels_forgotten, 0u);
  EXPECT_EQ(c.result.frames, 15u);
}

TEST(FreeSpaceCarving, AStaticSurfaceSeenFromGrazingAnglesIsKept) {
  // The camera walks along the east wall, 0.15 m from it, looking along it: most of the wall is seen at 2-10
  // degrees, where a pixel's ray meets it several centimetres off a point that projects a fraction of a pixel away.
  std::vector<View> views;
  for (int i = 0; i < 8; ++i) {
    const core::SE3 T_wc = testing::cameraPose({1.85, -1.8 + 0.1 * i, 1.2 + 0.02 * (i % 3)},
                                               M_PI / 2 - 0.05 * (i % 4), -0.1);
    views.push_back(viewOf(T_wc, {}));
  }
  DenseOptions o = carvingRoomOptions();  // the default voxel and band: a pixel (2 cm at 2 m) spans more than the band
  o.voxel_size = 0.02;             // along a wall seen at 5 degrees
  o.truncation = 0.06;
  const Carved c = fuseAndCarve(views, o);
  ASSERT_GT(c.before.size(), 3000u);
  EXPECT_LT(c.result.points.size(), c.before.size() / 500 + 1) << "carved " << c.result.points.size();
}

TEST(FreeSpaceCarving, NoiseWithinTheBandDoesNotCarve) {
  // The sensor's depth noise (sigma(z), structured light) on every reading of a room turned round in.
  std::mt19937 rng(7);
  std::normal_distribution<float> unit(0.f, 1.f);
  std::vector<View> views;
  for (int i = 0; i < 24; ++i) {
    View v = viewOf(testing::cameraPose({0.1, -0.2, 1.3}, 2 * M_PI * i / 24, -0.35), {});
    v.depth.forEach<float>([&](float& z, const int*) {
      z += static_cast<float>(DenseOptions::depthNoise(z)) * unit(rng);
    });
    views.push_back(v);
  }
  const Carved c = fuseAndCarve(views, carvingRoomOptions());
  ASSERT_GT(c.before.size(), 5000u);
  EXPECT_LT(c.result.points.size(), c.before.size() / 1000 + 1) << "carved " << c.result.points.size();
}

TEST(FreeSpaceCarving, ForgettingAVertexsVoxelsRemovesItFromTheMesh) {
  TsdfVolume volume(carvingRoomOptions());
  const View v = viewOf(testing::cameraPose({0, 0, 1.3}, 0, -0.2), {});
  volume.integrate(v.depth, v.bgr, testing::roomCamera(), v.T_wc.inverse());
  const std::vector<Eigen::Vector3d> before = volume.extractMesh()->vertices_;
  ASSERT_GT(before.size(), 100u);
  const Eigen::Vector3d gone = before[before.size() / 2];
  EXPECT_EQ(volume.forgetSurfaceAt({gone}), 2u);
  EXPECT_EQ(volume.forgetSurfaceAt({gone}), 0u);  // already forgotten
  const std::vector<Eigen::Vector3d> after = volume.extractMesh()->vertices_;
  EXPECT_LT(after.size(), before.size());
  for (const auto& p : after) ASSERT_GT((p - gone).norm(), 1e-6) << "the vertex is still there";
}

// One point 2 m in front of a camera at the origin looking along +z.
struct OnePoint {
  core::CameraIntrinsics k = testing::roomCamera();
  SeeThroughOptions options;
  SeeThroughVote vote{{Eigen::Vector3d(0, 0, 2)}, options};
  cv::Mat reading(float z) const { return cv::Mat(k.height, k.width, CV_32F, cv::Scalar(z)); }
  void add(float z) { vote.addFrame(reading(z), k, core::SE3::Identity()); }
};

TEST(SeeThroughVote, CountsSupportSeeThroughAndNothing) {
  OnePoint p;
  const double band = p.options.band(2.0);
  EXPECT_NEAR(band, 0.06 + 3 * DenseOptions::depthNoise(2.0), 1e-12);
  p.add(static_cast<float>(2.0 + 0.9 * band));  // within the band: support
  p.add(3.0f);                                   // far beyond: seen through
  p.add(1.0f);                                   // in front: hidden, no vote
  p.add(0.0f);                                   // no reading: no vote
  EXPECT_EQ(p.vote.counts(0).support, 1u);
  EXPECT_EQ(p.vote.counts(0).through, 1u);
  EXPECT_EQ(p.vote.frames(), 4u);
}

TEST(SeeThroughVote, ABandThatGrowsWithRange) {
  // At 3.9 m sigma is 19.9 mm: a reading 10 cm beyond is within 0.06 + 3 sigma there, not at 1 m.
  OnePoint near_point, far_point;
  far_point.vote = SeeThroughVote({Eigen::Vector3d(0, 0, 3.9)}, far_point.options);
  near_point.vote = SeeThroughVote({Eigen::Vector3d(0, 0, 1.0)}, near_point.options);
  far_point.add(4.0f);
  near_point.add(1.1f);
  EXPECT_EQ(far_point.vote.counts(0).support, 1u);
  EXPECT_EQ(near_point.vote.counts(0).through, 1u);
}

TEST(SeeThroughVote, NeedsMinVotesAndMoreThanTheSupport) {
  OnePoint p;  // min_votes 3
  p.add(3.0f);
  p.add(3.0f);
  EXPECT_FALSE(p.vote.seenThrough(0)) << "two frames are not enough";
  p.add(3.0f);
  EXPECT_TRUE(p.vote.seenThrough(0));
  for (int i = 0; i < 3; ++i) p.add(2.0f);
  EXPECT_FALSE(p.vote.seenThrough(0)) << "as often seen as seen through";
}

TEST(SeeThroughVote, EveryVoteSinceItWasLastSeenSeeingThroughItCarves) {
  // Seen for 10 frames (a person standing), then seen through for 5: fewer than the support, but all since.
  OnePoint p;
  p.options.recent_votes = 5;
  p.vote = SeeThroughVote({Eigen::Vector3d(0, 0, 2)}, p.options);
  for (int i = 0; i < 10; ++i) p.add(2.0f);
  for (int i = 0; i < 4; ++i) p.add(3.0f);
  EXPECT_FALSE(p.vote.seenThrough(0));
  p.add(3.0f);
  EXPECT_TRUE(p.vote.seenThrough(0));
  p.add(2.0f);  // seen again: the run starts anew, and 5 of 16 is no majority
  EXPECT_FALSE(p.vote.seenThrough(0));
}

TEST(SeeThroughVote, ANeighbourWithinTheBandIsNoSeeThrough) {
  // At a grazing angle the nearest pixel's ray meets the surface far behind the point, a neighbour's within the
  // band: no vote.
  OnePoint p;
  cv::Mat depth = p.reading(3.0f);
  const int u = static_cast<int>(std::lround(p.k.cx)), v = static_cast<int>(std::lround(p.k.cy));
  depth.at<float>(v, u + 1) = 2.02f;
  p.vote.addFrame(depth, p.k, core::SE3::Identity());
  EXPECT_EQ(p.vote.counts(0).through, 0u);
  EXPECT_EQ(p.vote.counts(0).support, 0u);
}

}  // namespace
}  // namespace amos::dense
