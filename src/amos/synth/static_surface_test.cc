#include "amos/synth/static_surface.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "amos/core/error.h"
#include "amos/testing/scratch_dir.h"

namespace amos::synth {
namespace {

namespace fs = std::filesystem;

TEST(StaticSurface, SamplesTheStaticSceneAlone) {
  SequenceOptions options;
  options.preset = "walking_static";  // a person walks in front of a still camera
  options.frames = 2;
  const SequenceGenerator generator(options);
  SurfaceSampling sampling;
  sampling.pixel_step = 8;
  const std::vector<SurfaceSample> samples = staticSurfaceSamples(generator, sampling);
  ASSERT_GT(samples.size(), 1000u);
  // Every sample lies on the static scene: its exact depth without movers at its pixel matches.
  const RenderedImage statics = generator.renderExact(0, true, false, false);
  const core::SE3 T_cw = generator.poseWc(0).inverse();
  const core::CameraIntrinsics& k = generator.intrinsics();
  int checked = 0;
  for (std::size_t i = 0; i < samples.size(); i += 97) {
    const Eigen::Vector3d p_c = T_cw * samples[i].position.cast<double>();
    const int u = int(std::lround(k.fx * p_c.x() / p_c.z() + k.cx)), v = int(std::lround(k.fy * p_c.y() / p_c.z() + k.cy));
    if (u < 0 || v < 0 || u >= k.width || v >= k.height) continue;
    EXPECT_NEAR(statics.depth.at<float>(v, u), p_c.z(), 0.05 * p_c.z());
    EXPECT_GE(samples[i].depth, 0.0f);
    ++checked;
  }
  EXPECT_GT(checked, 5);
}

TEST(StaticSurface, ReadsBackWhatItWrote) {
  const fs::path file = testing::scratchDirForThisTest("amos_surface_") / "surface.ply";
  const std::vector<SurfaceSample> samples = {{{1, 2, 3}, 1.5f}, {{-1, 0.5, 2}, 3.0f}};
  writeSurfacePly(file.string(), samples);
  const std::vector<SurfaceSample> back = readSurfacePly(file.string());
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].position, samples[1].position);
  EXPECT_EQ(back[1].depth, 3.0f);
  fs::remove(file);
  EXPECT_THROW(readSurfacePly(file.string()), core::Error);
}

}  // namespace
}  // namespace amos::synth
