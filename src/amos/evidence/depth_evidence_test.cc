#include "amos/evidence/depth_evidence.h"

#include <gtest/gtest.h>

#include <random>

#include "amos/core/option_error.h"
#include "amos/dynamic/test_scenes.h"
#include "amos/testing/test_camera.h"

namespace amos::evidence {

using namespace dynamic;  // NOLINT(google-build-using-namespace): the front end's types
namespace {

// A wall 3 m in front of the world origin (plane z = 3) and the front face of a box, a rectangle [x0, x1] x
// [y0, y1] on the plane z = box_z; cameras look along +z without rotation, from `centre`.
struct Box {
  double x0 = -0.3, x1 = 0.3, y0 = -0.3, y1 = 0.3, z = 1.5;
};

cv::Mat renderDepth(const core::PinholeCamera& camera, const Eigen::Vector3d& centre, const Box& box, double noise_m = 0,
                    unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_m > 0 ? noise_m : 1.0);
  cv::Mat depth(camera.height(), camera.width(), CV_32F);
  for (int v = 0; v < camera.height(); ++v)
    for (int u = 0; u < camera.width(); ++u) {
      const Eigen::Vector3d ray = camera.backProject(u, v, 1.0);
      const double t_box = box.z - centre.z();
      const Eigen::Vector3d hit = centre + t_box * ray;
      const bool on_box = t_box > 0 && hit.x() >= box.x0 && hit.x() <= box.x1 && hit.y() >= box.y0 && hit.y() <= box.y1;
      double z = on_box ? t_box : 3.0 - centre.z();
      if (noise_m > 0) z += noise(rng);
      depth.at<float>(v, u) = static_cast<float>(z);
    }
  return depth;
}

// Superpixels: 40 x 40 px blocks (test_scenes.h: blockLabels, blockAt).

struct DepthEvidenceScene {
  core::PinholeCamera camera = testing::testCamera();
  DepthEvidenceOptions options;
  DepthSampleGrid grid{camera, options.sample_step_px};
  int count = 0;
  cv::Mat labels = blockLabels(camera, count);

  DepthEvidence evidence(const Eigen::Vector3d& c_last, const Box& box_last, const Eigen::Vector3d& c_now,
                         const Box& box_now, bool free_space_only = false, double noise_m = 0,
                         const core::SE3& pose_error = core::SE3::Identity()) const {
    const cv::Mat last = renderDepth(camera, c_last, box_last, noise_m, 1);
    const cv::Mat now = renderDepth(camera, c_now, box_now, noise_m, 2);
    const core::SE3 T_cw_last = poseAt(c_last), T_cw = pose_error * poseAt(c_now);
    return superpixelDepthEvidence({now, T_cw}, {last, T_cw_last}, grid, {labels, count},
                                   {camera, 0.05, options, free_space_only});
  }
  // Pixel of a world point seen from `centre`.
  cv::Point pixel(const Eigen::Vector3d& centre, const Eigen::Vector3d& p_w) const {
    const Eigen::Vector2d u = camera.project(p_w - centre);
    return {static_cast<int>(u.x()), static_cast<int>(u.y())};
  }
};

TEST(DepthEvidence, StaticSceneSeenFromAMovingCameraDoesNotMove) {
  const DepthEvidenceScene s;
  const Box box;
  const DepthEvidence e = s.evidence({0, 0, 0}, box, {0.03, -0.01, 0.02}, box, false, 0.005);
  EXPECT_GT(e.samples, 15000);
  EXPECT_EQ(e.moving_superpixels, 0);
}

TEST(DepthEvidence, PoseErrorAtTheBoxEdgesDoesNotMoveThem) {
  // A 2 mrad rotation error (about a pixel) slides the box edge over the wall behind it: the samples within 2 px of
  // a depth edge in either frame do not count, so no superpixel moves.
  const DepthEvidenceScene s;
  const Box box;
  const core::SE3 error(Eigen::AngleAxisd(0.002, Eigen::Vector3d::UnitY()));
  const DepthEvidence e = s.evidence({0, 0, 0}, box, {0.02, 0, 0}, box, false, 0.0, error);
  EXPECT_EQ(e.moving_superpixels, 0);
}

TEST(DepthEvidence, BoxComingTowardsTheCameraMovesItsInsideOnly) {
  const DepthEvidenceScene s;
  Box before, after;
  after.z = 1.45;  // 5 cm nearer: 10 sigma of the 1.5 m noise, above the 1 cm floor
  const DepthEvidence e = s.evidence({0, 0, 0}, before, {0, 0, 0}, after, false, 0.003);
  const cv::Point centre = s.pixel({0, 0, 0}, {0, 0, 1.45});
  const int inside = blockAt(s.camera, centre.x - 20, centre.y - 20);
  EXPECT_TRUE(e.superpixels[inside].moving);
  EXPECT_NEAR(e.superpixels[inside].median_m, 0.05, 0.01);
  EXPECT_FALSE(e.superpixels[blockAt(s.camera, 20, 20)].moving);  // the wall
  // Only blocks that overlap the box (0.6 m at 1.45 m: ~221 px square, within 7 x 7 blocks), and most of them.
  EXPECT_GE(e.moving_superpixels, 25);
  EXPECT_LE(e.moving_superpixels, 49);
}

TEST(DepthEvidence, BoxGoingAwayMovesOverOneFrameButOnlyRecedesInFreeSpaceMode) {
  const DepthEvidenceScene s;
  Box before, after;
  after.z = 1.55;
  const cv::Point centre = s.pixel({0, 0, 0}, {0, 0, 1.55});
  const int inside = blockAt(s.camera, centre.x - 20, centre.y - 20);
  const DepthEvidence two_sided = s.evidence({0, 0, 0}, before, {0, 0, 0}, after, false, 0.003);
  EXPECT_TRUE(two_sided.superpixels[inside].moving);
  EXPECT_LT(two_sided.superpixels[inside].median_m, -0.04);
  const DepthEvidence free_space = s.evidence({0, 0, 0}, before, {0, 0, 0}, after, true, 0.003);
  EXPECT_FALSE(free_space.superpixels[inside].moving);
  EXPECT_TRUE(free_space.superpixels[inside].receded);
}

TEST(DepthEvidence, FlatBoxSlidingSidewaysViolatesFreeSpaceAtItsLeadingEdge) {
  // The box's flat face shows no depth change, but where it now stands the last frame saw the wall 1.5 m behind.
  const DepthEvidenceScene s;
  Box before, after;
  after.x0 += 0.1, after.x1 += 0.1;  // 35 px to the right at 1.5 m
  const DepthEvidence e = s.evidence({0, 0, 0}, before, {0, 0, 0}, after, true, 0.003);
  const cv::Point lead = s.pixel({0, 0, 0}, {after.x1 - 0.04, 0.0, 1.5});   // box now, wall before
  const cv::Point inner = s.pixel({0, 0, 0}, {0.1, 0.0, 1.5});              // box in both frames
  const cv::Point trail = s.pixel({0, 0, 0}, {before.x0 + 0.04, 0.0, 1.5});  // wall now, box before
  const SuperpixelDepth& leading = e.superpixels[blockAt(s.camera, lead.x, lead.y)];
  EXPECT_TRUE(leading.moving);
  EXPECT_GT(leading.violations, s.options.min_violations);
  EXPECT_FALSE(e.superpixels[blockAt(s.camera, inner.x, inner.y)].moving);
  EXPECT_FALSE(e.superpixels[blockAt(s.camera, trail.x, trail.y)].moving);
}

TEST(DepthEvidence, BaselineRecessionCountsOnlyWhileTheSurfaceStillRecedes) {
  DepthEvidence last, baseline;
  last.superpixels.resize(2);
  baseline.superpixels.resize(2);
  for (int s = 0; s < 2; ++s) {
    SuperpixelDepth& b = baseline.superpixels[s];  // 8 cm behind what the baseline saw
    b.samples = 40, b.median_m = -0.08, b.threshold_m = 0.01, b.standard_error_m = 0.002, b.receded = true;
    last.superpixels[s].samples = 40;
    last.superpixels[s].standard_error_m = 0.002;
  }
  last.superpixels[0].median_m = -0.006;  // still receding: 3 standard errors
  last.superpixels[1].median_m = -0.001;  // at rest now: background a mover uncovered
  const DepthEvidence both = combineDepthEvidence(last, baseline);
  EXPECT_TRUE(both.superpixels[0].moving);
  EXPECT_FALSE(both.superpixels[1].moving);
  EXPECT_EQ(both.moving_superpixels, 1);
  DepthEvidence other;
  other.superpixels.resize(3);
  EXPECT_THROW(combineDepthEvidence(last, other), core::Error);
}

TEST(DepthEvidence, ClustersFollowTheirSampleShareOrTheirMovingSuperpixelsWhenUnscored) {
  DepthEvidenceOptions options;
  DepthEvidence e;
  e.superpixels.resize(6);
  for (auto& sp : e.superpixels) sp.samples = 40;
  e.superpixels[0].moving = true;  // cluster 0: 1 of 2 moving: share 0.5
  e.superpixels[2].moving = true;  // cluster 1: 2 of 4 ... but 3 and 4 weigh more
  e.superpixels[3].moving = true;
  e.superpixels[4].samples = 400;
  e.superpixels[5].samples = 400;
  const std::vector<int> cluster = {0, 0, 1, 1, 1, 1};
  const std::vector<bool> moving_scored = depthMovingClusters(e, cluster, {true, true}, 2, options);
  EXPECT_TRUE(moving_scored[0]);
  EXPECT_FALSE(moving_scored[1]);  // 80 of 880 samples
  const std::vector<bool> moving_unscored = depthMovingClusters(e, cluster, {true, false}, 2, options);
  EXPECT_TRUE(moving_unscored[1]);  // two moving superpixels and no tracks to say otherwise
}

TEST(DepthEvidence, OptionsAreChecked) {
  DepthEvidenceOptions o;
  EXPECT_NO_THROW(o.check());
  o.sample_step_px = 0;
  EXPECT_THROW(o.check(), core::InvalidOption);
  o = {};
  o.cluster_share = 0;
  EXPECT_THROW(o.check(), core::InvalidOption);
  o = {};
  o.baseline_frames = -1;
  EXPECT_THROW(o.check(), core::InvalidOption);
  EXPECT_NEAR(DepthEvidenceOptions{}.sigma(0.4), 0.0012, 1e-12);
}

}  // namespace
}  // namespace amos::evidence
