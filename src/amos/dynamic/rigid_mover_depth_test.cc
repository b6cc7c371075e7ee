#include "amos/dynamic/rigid_mover_depth.h"

#include <gtest/gtest.h>

#include "amos/dynamic/test_scenes.h"

namespace amos::dynamic {
namespace {

// A plain wall 3 m away, and a plain panel in front of it covering `panel` (pixels) at panel_depth_m: no texture
// anywhere, so only the depth can say what moved. The camera stands still.
cv::Mat wallWithPanel(const core::PinholeCamera& camera, const cv::Rect& panel, float panel_depth_m) {
  cv::Mat depth(camera.height(), camera.width(), CV_32F, cv::Scalar(3.0f));
  depth(panel).setTo(cv::Scalar(panel_depth_m));
  return depth;
}

core::SE3 translation(double x, double y, double z) {
  core::SE3 T = core::SE3::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

// Per test block, the votes for the one mover (whose motion takes current-camera points to the baseline camera by
// T_bc, with its points' box `region`) and for the static world (identity: the camera stands still).
struct Votes {
  std::vector<int> mover, still;
  int mover_total = 0, still_total = 0;
};

Votes vote(const cv::Mat& depth, const cv::Mat& baseline_depth, const core::SE3& T_bc, const cv::Rect2f& region) {
  const core::PinholeCamera camera = testCamera();
  int count = 0;
  const cv::Mat labels = blockLabels(camera, count);
  const std::vector<RigidMover> movers{{T_bc, 20, 5.0, region}};
  Votes out;
  out.mover.assign(static_cast<std::size_t>(count), 0);
  out.still.assign(out.mover.size(), 0);
  for (const RigidSampleVote& v : rigidMoverDepthVotes(movers, core::SE3::Identity(), depth, baseline_depth, camera,
                                                       DepthSampleGrid(camera, 4), labels, count, 30, 0.05,
                                                       DepthEvidenceOptions{})) {
    EXPECT_TRUE(v.mover == 0 || v.mover == -1);
    if (v.mover == 0)
      ++out.mover[static_cast<std::size_t>(v.superpixel)], ++out.mover_total;
    else
      ++out.still[static_cast<std::size_t>(v.superpixel)], ++out.still_total;
  }
  return out;
}

TEST(RigidMoverDepth, APlainPanelThatRecededIsFoundWhereItNowIs) {
  // Ten frames ago the panel stood at 1.5 m, now at 1.62 m: 12 cm away from the camera, beyond the 4 % bar of a
  // ten-frame comparison (6 cm). From the current frame that looks like background uncovered by a mover (the
  // depth evidence leaves it undecided); from the baseline frame the current one sees through where it was.
  const core::PinholeCamera camera = testCamera();
  const cv::Rect panel(200, 120, 240, 240);  // blocks 5-10 x 3-8
  const cv::Mat baseline = wallWithPanel(camera, panel, 1.5f);
  // Receding along the optical axis about the image centre it shrinks by 1.5 / 1.62 around (cx, cy).
  const double s = 1.5 / 1.62, cx = camera.cx(), cy = camera.cy();
  const cv::Rect now_panel(cvRound(cx + (panel.x - cx) * s), cvRound(cy + (panel.y - cy) * s),
                           cvRound(panel.width * s), cvRound(panel.height * s));
  const cv::Mat current = wallWithPanel(camera, now_panel, 1.62f);
  // The mover's motion: a current point on the panel lies 12 cm nearer in the baseline camera.
  const Votes v = vote(current, baseline, translation(0, 0, -0.12), cv::Rect2f(now_panel));
  EXPECT_GT(v.mover_total, 500);
  const int cols = (camera.width() + kTestBlock - 1) / kTestBlock;
  for (int b = 0; b < static_cast<int>(v.mover.size()); ++b) {
    const cv::Rect block((b % cols) * kTestBlock, (b / cols) * kTestBlock, kTestBlock, kTestBlock);
    const cv::Rect inner(now_panel.x + 8, now_panel.y + 8, now_panel.width - 16, now_panel.height - 16);
    if ((block & inner) == block) {
      EXPECT_GE(v.mover[b], 90) << "panel block " << b;  // of its 100 samples
      EXPECT_EQ(v.still[b], 0) << "panel block " << b;
    }
    if ((block & now_panel).area() == 0) {
      // The wall, also the strip the panel uncovered: the baseline saw it nowhere (hidden), so nothing votes.
      EXPECT_EQ(v.mover[b], 0) << "wall block " << b;
    }
  }
}

TEST(RigidMoverDepth, AStaticSceneVotesForTheStaticWorldAndNeverForTheMover) {
  // Nothing moved; the "mover" claims its points were 12 cm farther ten frames ago. The current frame sees the
  // static panel where the mover predicts it 12 cm nearer: free space refutes the mover.
  const core::PinholeCamera camera = testCamera();
  const cv::Rect panel(200, 120, 240, 240);
  const cv::Mat depth = wallWithPanel(camera, panel, 1.5f);
  const Votes v = vote(depth, depth, translation(0, 0, 0.12), cv::Rect2f(panel));
  EXPECT_EQ(v.mover_total, 0);
  EXPECT_GT(v.still_total, 500);
}

TEST(RigidMoverDepth, AMotionThatCarriesPointsOntoAStaticSurfaceGetsNoVote) {
  // Ten frames ago a box stood at A (1.5 m); now A shows the wall behind it. A motion fitted wrong carries A onto B,
  // a static panel at the same depth that both frames see: the static world refuted at A, the "mover" supported at
  // B. But B's current points, moved back by the static world, match what the baseline saw there: no vote.
  const core::PinholeCamera camera = testCamera();
  const cv::Rect a(100, 120, 120, 120), b(400, 120, 120, 120);
  cv::Mat baseline = wallWithPanel(camera, a, 1.5f);
  baseline(b).setTo(cv::Scalar(1.5f));
  const cv::Mat current = wallWithPanel(camera, b, 1.5f);
  const double shift_m = 300.0 * 1.5 / camera.fx();  // A -> B at 1.5 m
  const Votes v = vote(current, baseline, translation(-shift_m, 0, 0), cv::Rect2f(b));
  EXPECT_EQ(v.mover_total, 0);
  // Without the static panel at B in the baseline (B is new: a box that moved there), the same motion is right.
  const cv::Mat moved_baseline = wallWithPanel(camera, a, 1.5f);
  const Votes w = vote(current, moved_baseline, translation(-shift_m, 0, 0), cv::Rect2f(b));
  EXPECT_GT(w.mover_total, 500);
}

TEST(RigidMoverDepth, AMotionWithinTheNoiseDecidesNothing) {
  // 2 cm at 1.5 m is below the 1-cm / 2 % support bar's double and the 4 % refutation bar: no vote either way.
  const core::PinholeCamera camera = testCamera();
  const cv::Rect panel(200, 120, 240, 240);
  const cv::Mat baseline = wallWithPanel(camera, panel, 1.5f);
  const cv::Mat current = wallWithPanel(camera, panel, 1.52f);
  const Votes v = vote(current, baseline, translation(0, 0, -0.02), cv::Rect2f(panel));
  EXPECT_EQ(v.mover_total + v.still_total, 0);
}

TEST(RigidMoverDepth, NoMoverNoVotes) {
  const core::PinholeCamera camera = testCamera();
  int count = 0;
  const cv::Mat labels = blockLabels(camera, count);
  const cv::Mat depth = wallWithPanel(camera, cv::Rect(200, 120, 240, 240), 1.5f);
  EXPECT_TRUE(rigidMoverDepthVotes({}, core::SE3::Identity(), depth, depth, camera, DepthSampleGrid(camera, 4),
                                   labels, count, 30, 0.05, DepthEvidenceOptions{})
                  .empty());
}

}  // namespace
}  // namespace amos::dynamic
