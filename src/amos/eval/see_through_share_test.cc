// The ghost measure without ground truth against the one with it, on a synthetic sequence rendered in memory: the
// people of one early frame planted in a mesh of the static room are what the swept volume calls ghosts, and what
// the sequence's own frames see through; the room is neither.
#include "amos/eval/see_through_share.h"

#include <gtest/gtest.h>

#include "amos/eval/mesh_eval.h"
#include "amos/synth/sequence.h"
#include "amos/synth/swept_volume.h"

namespace amos::eval {
namespace {

// Every `step`-th pixel of an exact render of frame `index` (the static room or the movers alone), in the world.
std::vector<Eigen::Vector3d> surfaceOf(const synth::SequenceGenerator& gen, int index, bool movers, int step) {
  const synth::RenderedImage image = gen.renderExact(index, !movers, movers, false);
  const core::SE3 T_wc = gen.poseWc(index);
  const core::CameraIntrinsics& k = gen.intrinsics();
  std::vector<Eigen::Vector3d> out;
  for (int v = 0; v < image.depth.rows; v += step) {
    for (int u = 0; u < image.depth.cols; u += step) {
      const float z = image.depth.at<float>(v, u);
      if (z > 0 && z < 4.0f) out.push_back(T_wc * Eigen::Vector3d((u - k.cx) * z / k.fx, (v - k.cy) * z / k.fy, z));
    }
  }
  return out;
}

TEST(SeeThroughShare, AgreesWithTheSweptVolumeGhostsOnSyntheticTruth) {
  synth::SequenceOptions options;
  options.preset = "walking_xyz";
  options.seed = 1;
  options.frames = 60;
  const synth::SequenceGenerator gen(options);
  const std::vector<Eigen::Vector3d> room = surfaceOf(gen, 30, false, 6);
  // The people where they stood in the early frame that shows most of them: a mask that missed them there.
  std::vector<Eigen::Vector3d> people;
  for (int index = 0; index < 20; index += 4) {
    std::vector<Eigen::Vector3d> there = surfaceOf(gen, index, true, 3);
    if (there.size() > people.size()) people = std::move(there);
  }
  ASSERT_GT(people.size(), 300u);
  std::vector<Eigen::Vector3d> mesh = room;
  mesh.insert(mesh.end(), people.begin(), people.end());

  const MeshScore truth = scoreMesh(mesh, surfaceOf(gen, 30, false, 2), synth::sweptVolumeOf(gen), 0.04, 0.04);
  SeeThroughScorer scorer(mesh, gen.intrinsics(), dense::DenseOptions{});
  for (int i = 0; i < gen.frameCount(); ++i) scorer.addFrame(gen.render(i).depth, gen.poseWc(i));
  const SeeThroughScore s = scorer.score();

  std::size_t room_through = 0, people_through = 0;
  SeeThroughScorer room_only(room, gen.intrinsics(), dense::DenseOptions{});
  for (int i = 0; i < gen.frameCount(); ++i) room_only.addFrame(gen.render(i).depth, gen.poseWc(i));
  room_through = room_only.score().seen_through;
  people_through = s.seen_through - room_through;
  std::printf("room %zu of %zu seen through, people %zu of %zu; ghosts by the sweep %zu (%.3f), seen through %.3f\n",
              room_through, room.size(), people_through, people.size(), truth.ghosts, truth.ghost_share, s.share);
  EXPECT_LT(room_through, room.size() / 200 + 1);
  EXPECT_GT(people_through, people.size() / 2);
  EXPECT_NEAR(s.share, truth.ghost_share, 0.3 * truth.ghost_share);
}

}  // namespace
}  // namespace amos::eval
