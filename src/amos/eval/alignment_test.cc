#include "amos/eval/alignment.h"

#include <gtest/gtest.h>

#include <random>

#include "amos/core/error.h"

namespace amos::eval {
namespace {

struct Synthetic {
  std::vector<Eigen::Vector3d> model, data;
};

// data = s * R * model + t (+ noise), model points spread over a few metres like a hand-held trajectory.
Synthetic makePoints(const core::SE3& T, double scale, double noise_sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::normal_distribution<double> noise(0.0, noise_sigma > 0 ? noise_sigma : 1.0);
  Synthetic s;
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d m(u(rng), 0.5 * u(rng), 0.25 * u(rng));
    Eigen::Vector3d d = T.linear() * (scale * m) + T.translation();
    if (noise_sigma > 0) d += Eigen::Vector3d(noise(rng), noise(rng), noise(rng)) * 1.0;
    s.model.push_back(m);
    s.data.push_back(d);
  }
  return s;
}

core::SE3 knownTransform() {
  return core::expSE3((core::Vector6d() << 1.5, -0.7, 2.2, 0.4, -1.1, 2.5).finished());
}

// Frobenius distance of the rotation blocks (an arccos-based angle would be limited to ~1e-8 by round-off).
double rotationError(const core::SE3& a, const core::SE3& b) { return (a.linear() - b.linear()).norm(); }

TEST(Alignment, RecoversARigidTransformExactly) {
  const core::SE3 T = knownTransform();
  const Synthetic s = makePoints(T, 1.0, 0.0, 1);
  const Alignment a = alignPoints(s.model, s.data, false);
  EXPECT_LT(rotationError(a.transform, T), 1e-12);
  EXPECT_LT((a.transform.translation() - T.translation()).norm(), 1e-12);
  EXPECT_EQ(a.scale, 1.0);
  for (std::size_t i = 0; i < s.model.size(); ++i) EXPECT_LT((a.apply(s.model[i]) - s.data[i]).norm(), 1e-12);
}

TEST(Alignment, RecoversASimilarityTransformExactly) {
  const core::SE3 T = knownTransform();
  const Synthetic s = makePoints(T, 2.7, 0.0, 2);
  const Alignment a = alignPoints(s.model, s.data, true);
  EXPECT_NEAR(a.scale, 2.7, 1e-12);
  EXPECT_LT(rotationError(a.transform, T), 1e-12);
  EXPECT_LT((a.transform.translation() - T.translation()).norm(), 1e-11);
}

TEST(Alignment, NoisyPointsGiveTheTransformToWithinTheNoiseLevel) {
  const core::SE3 T = knownTransform();
  const Synthetic rigid = makePoints(T, 1.0, 0.01, 3);
  const Alignment a = alignPoints(rigid.model, rigid.data, false);
  // 500 points, 1 cm noise: rotation to ~1e-3 rad, translation to a few mm.
  EXPECT_LT(rotationError(a.transform, T), 3e-3);
  EXPECT_LT((a.transform.translation() - T.translation()).norm(), 3e-3);

  const Synthetic similar = makePoints(T, 0.35, 0.01, 4);
  const Alignment b = alignPoints(similar.model, similar.data, true);
  EXPECT_NEAR(b.scale, 0.35, 5e-3);
  EXPECT_LT(rotationError(b.transform, T), 1e-2);
  EXPECT_LT((b.transform.translation() - T.translation()).norm(), 5e-3);
}

TEST(Alignment, RigidAlignmentOfAScaledCopyDoesNotInventAScale) {
  const Synthetic s = makePoints(knownTransform(), 2.0, 0.0, 5);
  const Alignment a = alignPoints(s.model, s.data, false);
  EXPECT_EQ(a.scale, 1.0);
  EXPECT_LT(rotationError(a.transform, knownTransform()), 1e-12);  // rotation is still found
}

TEST(Alignment, NeverReturnsAReflection) {
  // Data is a mirror image of the model: the best proper rotation, not the reflection, must come out.
  const Synthetic s = makePoints(core::SE3::Identity(), 1.0, 0.0, 6);
  std::vector<Eigen::Vector3d> mirrored;
  for (const auto& p : s.data) mirrored.emplace_back(p.x(), p.y(), -p.z());
  const Alignment a = alignPoints(s.model, mirrored, false);
  EXPECT_NEAR(a.transform.linear().determinant(), 1.0, 1e-12);
}

TEST(Alignment, PoseApplicationRotatesAndMovesTheCamera) {
  Alignment a;
  a.transform = knownTransform();
  a.scale = 2.0;
  core::SE3 T_wc = core::expSE3((core::Vector6d() << 0.1, 0.2, 0.3, 0.01, 0.02, 0.03).finished());
  const core::SE3 out = a.apply(T_wc);
  EXPECT_LT((out.translation() - a.apply(Eigen::Vector3d(T_wc.translation()))).norm(), 1e-15);
  EXPECT_LT((out.linear() - a.transform.linear() * T_wc.linear()).norm(), 1e-15);
}

TEST(Alignment, RejectsTooFewOrMismatchedPoints) {
  EXPECT_THROW(alignPoints({Eigen::Vector3d::Zero()}, {Eigen::Vector3d::Zero()}, false), core::Error);
  EXPECT_THROW(alignPoints({Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()}, {Eigen::Vector3d::Zero()}, false),
               core::Error);
}

}  // namespace
}  // namespace amos::eval
