#include "amos/dynamic/epipolar_evidence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "amos/dynamic/test_scenes.h"

namespace amos::dynamic {
namespace {

// 120 static tracks of a scene 1-4 m deep seen from two poses, then 8 movers: static tracks pushed 6 px across their
// epipolar lines (the true F's).
struct Scene {
  std::vector<PointTrack> tracks;
  std::vector<bool> moving;
};

Scene makeScene() {
  const core::PinholeCamera camera = testCamera();
  const Eigen::Matrix3d K = camera.eigenK();
  core::Vector6d xi;
  xi << 0.05, -0.01, 0.02, 0.01, 0.03, -0.02;  // last camera -> current camera
  const core::SE3 T_cl = core::expSE3(xi);
  const Eigen::Matrix3d F = fundamentalFromPose(K, T_cl);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(30, 610), v(30, 450), z(1.0, 4.0);
  Scene scene;
  for (int i = 0; i < 128; ++i) {
    const Eigen::Vector3d p_l = K.inverse() * Eigen::Vector3d(u(rng), v(rng), 1.0) * z(rng);
    const Eigen::Vector2d a = (K * p_l).hnormalized();
    Eigen::Vector2d b = (K * (T_cl * p_l)).hnormalized();
    const bool moving = i >= 120;
    if (moving) b += 6.0 * (F * a.homogeneous()).head<2>().normalized();
    scene.tracks.push_back({cv::Point2f(a.x(), a.y()), cv::Point2f(b.x(), b.y())});
    scene.moving.push_back(moving);
  }
  return scene;
}

TEST(EpipolarEvidence, FitOutsideTheMoversFindsThemAsViolators) {
  const Scene scene = makeScene();
  std::vector<bool> fit_tracks(scene.moving.size());
  for (std::size_t i = 0; i < fit_tracks.size(); ++i) fit_tracks[i] = !scene.moving[i];
  DynamicDiagnostics diag;
  const EpipolarEvidence evidence =
      fitEpipolarEvidence(scene.tracks, fit_tracks, testCamera(), EpipolarOptions{}, diag);
  ASSERT_TRUE(evidence.fit.ok);
  EXPECT_TRUE(diag.fundamental_ok);
  EXPECT_EQ(diag.f_fit_points, 120);
  EXPECT_EQ(diag.f_final_inliers, evidence.fit.final_inliers);
  ASSERT_EQ(evidence.distance_px.size(), scene.tracks.size());
  std::vector<cv::Point2f> movers;
  for (std::size_t i = 0; i < scene.tracks.size(); ++i) {
    if (scene.moving[i]) {
      movers.push_back(scene.tracks[i].current);
      EXPECT_NEAR(evidence.distance_px[i], 6.0, 0.1) << i;  // 6 px, minus what float pixels lose
    } else {
      EXPECT_LT(evidence.distance_px[i], 0.05) << i;
    }
  }
  EXPECT_EQ(evidence.violators, movers);
  EXPECT_EQ(diag.dynamic_points, 8);
}

TEST(EpipolarEvidence, TooFewTracksOutsideMeansFittingOnAll) {
  const Scene scene = makeScene();
  std::vector<bool> fit_tracks(scene.tracks.size(), false);
  for (int i = 0; i < 40; ++i) fit_tracks[i] = true;  // below Dynamic.Epipolar.minFitPoints (50)
  DynamicDiagnostics diag;
  const EpipolarEvidence evidence =
      fitEpipolarEvidence(scene.tracks, fit_tracks, testCamera(), EpipolarOptions{}, diag);
  EXPECT_TRUE(evidence.fit.ok);
  EXPECT_EQ(diag.f_fit_points, 128);
}

TEST(EpipolarEvidence, WithoutFEveryDistanceIsInfiniteAndNothingViolates) {
  Scene scene = makeScene();
  scene.tracks.resize(10);  // F needs 15
  DynamicDiagnostics diag;
  const EpipolarEvidence evidence =
      fitEpipolarEvidence(scene.tracks, std::vector<bool>(10, true), testCamera(), EpipolarOptions{}, diag);
  EXPECT_FALSE(evidence.fit.ok);
  EXPECT_FALSE(diag.fundamental_ok);
  for (double d : evidence.distance_px) EXPECT_TRUE(std::isinf(d));
  EXPECT_TRUE(evidence.violators.empty());
  EXPECT_EQ(diag.dynamic_points, 0);
}

}  // namespace
}  // namespace amos::dynamic
