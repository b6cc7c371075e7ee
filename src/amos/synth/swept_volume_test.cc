#include "amos/synth/swept_volume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "amos/core/error.h"
#include "amos/synth/sequence.h"
#include "amos/testing/scratch_dir.h"

namespace amos::synth {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;

std::vector<double> frameTimes(double duration, double fps = 30) {
  std::vector<double> t;
  for (int k = 0; k <= std::lround(duration * fps); ++k) t.push_back(k / fps);
  return t;
}

// A box of `size` standing on the floor, its centre at x = speed * t.
GeometryAt pushedBox(const Vector3d& size, double speed) {
  return [size, speed](double t) {
    SceneGeometry g;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Vector3d(speed * t, 0, size.z() / 2);
    g.addBox(pose, size, allFaces(Surface{}), 1);
    return g;
  };
}

TEST(SweptVolume, ABoxPushedAlongAKnownPathSweepsItsTrail) {
  // 0.4 x 0.3 x 0.5 m box pushed 1 m along x in 1 s: it sweeps x in [-0.2, 1.2], |y| <= 0.15, z in [0, 0.5].
  const SweptVolume v = sweep(pushedBox({0.4, 0.3, 0.5}, 1.0), frameTimes(1.0), {});
  EXPECT_DOUBLE_EQ(v.cell(), 0.02);
  for (const Vector3d& p : {Vector3d(0.5, 0, 0.25), Vector3d(1.15, 0.13, 0.45), Vector3d(-0.15, -0.12, 0.05),
                            Vector3d(0.77, 0.07, 0.01)})
    EXPECT_TRUE(v.containsPoint(p)) << p.transpose();
  for (const Vector3d& p : {Vector3d(1.25, 0, 0.25), Vector3d(0.5, 0.2, 0.25), Vector3d(0.5, 0, 0.55),
                            Vector3d(-0.25, 0, 0.25), Vector3d(3, 2, 1)})
    EXPECT_FALSE(v.containsPoint(p)) << p.transpose();
  // The trail's volume, 1.4 x 0.3 x 0.5 = 0.21 m^3, grown by at most half a cell on every side.
  EXPECT_GT(v.volumeM3(), 0.20);
  EXPECT_LT(v.volumeM3(), 1.44 * 0.34 * 0.54);
  EXPECT_EQ(v.distanceTo({0.5, 0, 0.25}, 0.05), 0.0);
  EXPECT_NEAR(v.distanceTo({0.5, 0, 0.58}, 0.1), 0.06, 0.021);  // the top cells end at most a cell above 0.5
  EXPECT_TRUE(std::isinf(v.distanceTo({0.5, 0, 0.9}, 0.1)));
}

TEST(SweptVolume, AFastThinPlateLeavesNoGaps) {
  // A 2 cm plate at 3 m/s moves 10 cm between frames: the instants between frames fill the trail.
  const SweptVolume v = sweep(pushedBox({0.02, 0.3, 0.5}, 3.0), frameTimes(1.0), {});
  for (double x = 0; x <= 3.0; x += 0.01) ASSERT_TRUE(v.containsPoint({x, 0, 0.25})) << x;
  SweptVolumeOptions frames_only;
  frames_only.max_step = 1.0;  // one instant per frame: the plate leaves stripes
  const SweptVolume stripes = sweep(pushedBox({0.02, 0.3, 0.5}, 3.0), frameTimes(1.0), frames_only);
  EXPECT_LT(stripes.size(), v.size() / 2);
}

TEST(SweptVolume, SolidsByTheirInsideOpenSurfacesByAThinSlab) {
  SceneGeometry solids;
  solids.addSphere({0, 0, 1}, 0.1, Surface{}, 1);
  solids.addCylinder({1, 0, 0}, {1, 0, 1}, 0.1, Surface{}, 1);
  solids.addBox(Vector3d(2, -0.25, 0), Vector3d(2.5, 0.25, 0.5), allFaces(Surface{}), 1);
  SweptVolume v;
  v.mark(solids, 0.01);
  EXPECT_TRUE(v.containsPoint({0, 0, 1}));        // the sphere's centre
  EXPECT_FALSE(v.containsPoint({0.15, 0, 1}));
  EXPECT_TRUE(v.containsPoint({1, 0, 0.5}));      // the cylinder's axis
  EXPECT_TRUE(v.containsPoint({1, 0, 0.995}));    // under its cap
  EXPECT_FALSE(v.containsPoint({1, 0, 1.05}));
  EXPECT_TRUE(v.containsPoint({2.25, 0, 0.25}));  // the box's centre
  EXPECT_NEAR(v.volumeM3(), 4.0 / 3 * M_PI * std::pow(0.1, 3) + M_PI * 0.01 + 0.125, 0.03);

  // The same box as six open (two-sided) quads: a shell, the inside is left empty.
  SceneGeometry shell;
  shell.addBox(Vector3d(2, -0.25, 0), Vector3d(2.5, 0.25, 0.5), allFaces(Surface{}), 1);
  for (Quad& q : shell.quads) q.cull_back = false;
  SweptVolume s;
  s.mark(shell, 0.01);
  EXPECT_FALSE(s.containsPoint({2.25, 0, 0.25}));
  EXPECT_TRUE(s.containsPoint({2.0, 0, 0.25}));
  EXPECT_TRUE(s.containsPoint({2.01, 0.1, 0.3}));   // within the slab of a face
  EXPECT_FALSE(s.containsPoint({2.07, 0.1, 0.3}));  // beyond it
}

TEST(SweptVolume, ReadsBackWhatItWrote) {
  const fs::path file = testing::scratchDirForThisTest("amos_swept_") / "swept.ply";
  SweptVolumeOptions options;
  options.cell = 0.05;
  const SweptVolume v = sweep(pushedBox({0.4, 0.3, 0.5}, 1.0), frameTimes(0.5), options);
  writeSweptVolumePly(file.string(), v);
  const SweptVolume back = readSweptVolumePly(file.string());
  EXPECT_DOUBLE_EQ(back.cell(), 0.05);
  EXPECT_EQ(back.centres(), v.centres());
  writeSweptVolumePly(file.string(), SweptVolume(0.02));  // no movers: an empty volume
  EXPECT_TRUE(readSweptVolumePly(file.string()).empty());
  std::ofstream(file) << "ply\nformat ascii 1.0\nend_header\n";
  EXPECT_THROW(readSweptVolumePly(file.string()), core::Error);
  fs::remove(file);
  EXPECT_THROW(readSweptVolumePly(file.string()), core::Error);
}

TEST(SweptVolume, HoldsWhatTheCameraSawOfTheMovers) {
  SequenceOptions options;
  options.preset = "walking_static";  // a person walks in front of a still camera
  options.frames = 30;
  const SequenceGenerator generator(options);
  const SweptVolume v = sweptVolumeOf(generator);
  ASSERT_FALSE(v.empty());
  // Every pixel of the movers, back-projected from its exact depth, lies in (or on the border of) a marked cell.
  const core::CameraIntrinsics& k = generator.intrinsics();
  int seen = 0, inside = 0;
  for (int frame = 0; frame < generator.frameCount(); frame += 7) {
    const RenderedImage movers = generator.renderExact(frame, false, true, false);
    const core::SE3 T_wc = generator.poseWc(frame);
    for (int r = 0; r < movers.depth.rows; r += 2)
      for (int c = 0; c < movers.depth.cols; c += 2) {
        const float z = movers.depth.at<float>(r, c);
        if (!(z > 0)) continue;
        ++seen;
        inside += v.distanceTo(T_wc * Vector3d((c - k.cx) * z / k.fx, (r - k.cy) * z / k.fy, z), 0.005) <= 0.005;
      }
  }
  ASSERT_GT(seen, 500);
  EXPECT_EQ(inside, seen);
  // The same sequence without movers sweeps nothing.
  options.movers = false;
  EXPECT_TRUE(sweptVolumeOf(SequenceGenerator(options)).empty());
}

}  // namespace
}  // namespace amos::synth
