#include "amos/geometry/photometric_alignment.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

namespace amos::geometry {
namespace {

// A textured plane z = 2 m in the reference camera, seen by a 320x240 pinhole camera: its grey value at (X, Y) is a
// sum of sinusoids with periods of 8-16 cm (15-25 px at 2 m), so every pixel has a gradient.
constexpr double kF = 300, kCx = 159.5, kCy = 119.5, kPlaneZ = 2.0;
constexpr int kW = 320, kH = 240;

double texture(double X, double Y) {
  return 128 + 40 * std::sin(45 * X) + 30 * std::sin(38 * Y + 1) + 20 * std::sin(60 * (X + Y)) +
         15 * std::sin(70 * X - 50 * Y);
}

StereoProjection camera() { return {kF, kF, kCx, kCy, 0}; }

// TUM fr2's lens (the strongest of the datasets'): at this camera's corners it moves pixels by about 10 px.
core::RadialTangential fr2Lens() { return {0.231222, -0.784899, -0.003257, -0.000105, 0.917205}; }

// Renders the plane from a camera at T_cr (maps reference points into this camera) into the raw pixels of a camera
// with distortion `lens`: grey image and depth.
void render(const core::SE3& T_cr, cv::Mat& gray, cv::Mat& depth, double gain = 1, double bias = 0,
            const core::RadialTangential& lens = {}) {
  gray.create(kH, kW, CV_8U);
  depth.create(kH, kW, CV_32F);
  const core::SE3 T_rc = T_cr.inverse();
  const Eigen::Vector3d o = T_rc.translation();
  for (int v = 0; v < kH; ++v) {
    for (int u = 0; u < kW; ++u) {
      const Eigen::Vector2d xn = lens.undistort({(u - kCx) / kF, (v - kCy) / kF});
      const Eigen::Vector3d ray_c(xn.x(), xn.y(), 1);
      const Eigen::Vector3d ray_r = T_rc.linear() * ray_c;
      const double s = (kPlaneZ - o.z()) / ray_r.z();
      const Eigen::Vector3d p = o + s * ray_r;
      gray.at<std::uint8_t>(v, u) = cv::saturate_cast<std::uint8_t>(gain * texture(p.x(), p.y()) + bias);
      depth.at<float>(v, u) = static_cast<float>(s * ray_c.z());
    }
  }
}

struct Scene {
  core::SE3 T_cr_true;
  PhotometricTemplate reference;
  PhotometricImage current;
  std::vector<PoseObservation> no_features;
};

PhotometricOptions options() {
  PhotometricOptions o;
  o.cell = 6;
  return o;
}

// `lens`: the distortion the images are rendered with; `assumed_lens`: the one the refinement is told about.
Scene makeScene(double gain, double bias, const cv::Rect& mover, bool mask_mover,
                const core::RadialTangential& lens = {}, const core::RadialTangential& assumed_lens = {}) {
  Scene s;
  s.T_cr_true = core::expSE3((core::Vector6d() << 0.03, -0.01, 0.02, 0.01, -0.015, 0.005).finished());
  cv::Mat gray_r, depth_r, gray_c, depth_c;
  render(core::SE3::Identity(), gray_r, depth_r, 1, 0, lens);
  render(s.T_cr_true, gray_c, depth_c, gain, bias, lens);
  cv::Mat mask = cv::Mat::zeros(kH, kW, CV_8U);
  if (mover.area() > 0) {
    cv::randu(gray_c(mover), 0, 255);  // something moved in front of the plane
    if (mask_mover) mask(mover).setTo(255);
  }
  const PhotometricOptions o = options();
  const PhotometricImage reference = makePhotometricImage(gray_r, cv::Mat(), camera(), assumed_lens, o);
  s.reference = makePhotometricTemplate(reference, depth_r, o);
  s.current = makePhotometricImage(gray_c, mask, camera(), assumed_lens, o);
  return s;
}

// Translation (m) and rotation (rad) of the error between two poses.
std::pair<double, double> errorOf(const core::SE3& a, const core::SE3& b) {
  const core::Vector6d d = core::logSE3(a * b.inverse());
  return {d.head<3>().norm(), d.tail<3>().norm()};
}

PhotometricResult refine(const Scene& s, const core::SE3& initial_T_cw) {
  PhotometricProblem p;
  p.features = &s.no_features;
  p.projection = camera();
  p.reference = &s.reference;
  p.T_rw = core::SE3::Identity();  // the reference camera is the world
  p.current = &s.current;
  return refinePosePhotometrically(p, initial_T_cw, options());
}

core::SE3 perturbed(const core::SE3& T) {
  return core::expSE3((core::Vector6d() << 0.006, -0.004, 0.005, 0.004, 0.003, -0.002).finished()) * T;
}

TEST(PhotometricAlignment, TemplateKeepsHighGradientPixelsWithDepthOnEveryLevel) {
  const Scene s = makeScene(1, 0, {}, false);
  ASSERT_EQ(s.reference.levels.size(), 2u);
  for (const auto& level : s.reference.levels) {
    EXPECT_GT(level.size(), 500u);
    for (const PhotometricPoint& p : level) EXPECT_NEAR(p.p_r.z(), kPlaneZ, 1e-4);
  }
}

TEST(PhotometricAlignment, RecoversThePoseFromAPerturbedStart) {
  const Scene s = makeScene(1, 0, {}, false);
  const core::SE3 start = perturbed(s.T_cr_true);
  const auto [t0, r0] = errorOf(start, s.T_cr_true);
  const PhotometricResult r = refine(s, start);
  ASSERT_TRUE(r.accepted);
  const auto [t, rot] = errorOf(r.T_cw, s.T_cr_true);
  EXPECT_LT(t, 0.0005) << "from " << t0;
  EXPECT_LT(rot, 0.0003) << "from " << r0;
  EXPECT_GT(r.points, 500);
}

TEST(PhotometricAlignment, AnExposureChangeIsAbsorbedByTheBrightnessFit) {
  const Scene s = makeScene(1.25, -12, {}, false);
  const PhotometricResult r = refine(s, perturbed(s.T_cr_true));
  ASSERT_TRUE(r.accepted);
  EXPECT_LT(errorOf(r.T_cw, s.T_cr_true).first, 0.0005);
}

TEST(PhotometricAlignment, MaskedPixelsTakeNoPart) {
  const cv::Rect mover(40, 30, 150, 140);  // a third of the view
  const Scene masked = makeScene(1, 0, mover, true);
  const PhotometricResult r = refine(masked, perturbed(masked.T_cr_true));
  ASSERT_TRUE(r.accepted);
  EXPECT_LT(errorOf(r.T_cw, masked.T_cr_true).first, 0.0005);
  const Scene unmasked = makeScene(1, 0, mover, false);
  const PhotometricResult u = refine(unmasked, perturbed(unmasked.T_cr_true));
  EXPECT_GT(u.points, r.points) << "the masked pixels must be left out";
}

// The pixels' information (what bundle adjustment keeps of the alignment) is a proper information matrix and
// counts the pixels used: half the template points leave about half of it.
TEST(PhotometricAlignment, TheInformationIsPositiveDefiniteAndCountsThePixels) {
  const Scene full = makeScene(1, 0, {}, false);
  Scene half = makeScene(1, 0, {}, false);
  for (auto& level : half.reference.levels) level.resize(level.size() / 2);
  const PhotometricResult f = refine(full, perturbed(full.T_cr_true));
  const PhotometricResult h = refine(half, perturbed(half.T_cr_true));
  ASSERT_TRUE(f.accepted && h.accepted);
  for (const PhotometricResult* r : {&f, &h}) {
    EXPECT_LT((r->information - r->information.transpose()).norm(), 1e-9 * r->information.norm());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(r->information);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0);
  }
  EXPECT_GT(h.information.trace(), 0.3 * f.information.trace());
  EXPECT_LT(h.information.trace(), 0.7 * f.information.trace());
}

TEST(PhotometricAlignment, TooFewPointsLeaveThePoseAsItWas) {
  Scene s = makeScene(1, 0, {}, false);
  for (auto& level : s.reference.levels) level.resize(50);  // under min_points (200)
  const core::SE3 start = perturbed(s.T_cr_true);
  const PhotometricResult r = refine(s, start);
  EXPECT_FALSE(r.accepted);
  EXPECT_LT(errorOf(r.T_cw, start).first, 1e-12);
}

// Raw (distorted) images are sampled through the lens model: the pose is recovered as precisely as with a pinhole
// camera. Told no lens, the same images leave an error several times larger (the test can fail).
TEST(PhotometricAlignment, RecoversThePoseThroughALensDistortion) {
  const Scene s = makeScene(1, 0, {}, false, fr2Lens(), fr2Lens());
  const PhotometricResult r = refine(s, perturbed(s.T_cr_true));
  ASSERT_TRUE(r.accepted);
  const auto [t, rot] = errorOf(r.T_cw, s.T_cr_true);
  EXPECT_LT(t, 0.0005);
  EXPECT_LT(rot, 0.0003);
  EXPECT_GT(r.points, 500);
  const Scene ignored = makeScene(1, 0, {}, false, fr2Lens(), {});
  const PhotometricResult u = refine(ignored, perturbed(ignored.T_cr_true));
  EXPECT_TRUE(!u.accepted || errorOf(u.T_cw, ignored.T_cr_true).first > 3 * t);
}

// A template point is back-projected along the undistorted ray of the raw pixel it was selected at: projected
// back through the lens, it lands on that pixel (integer coordinates, the pixel's own grey value), on every level.
TEST(PhotometricAlignment, TemplatePointsReprojectOntoTheirRawPixels) {
  const core::RadialTangential lens = fr2Lens();
  cv::Mat gray, depth;
  render(core::SE3::Identity(), gray, depth, 1, 0, lens);
  const PhotometricOptions o = options();
  const PhotometricImage image = makePhotometricImage(gray, cv::Mat(), camera(), lens, o);
  const PhotometricTemplate t = makePhotometricTemplate(image, depth, o);
  double farthest = 0;  // distance of a point's pixel from where a pinhole camera would put it
  for (int l = 0; l < image.levels(); ++l) {
    const StereoProjection& k = image.intrinsics[l];
    ASSERT_GT(t.levels[l].size(), 100u);
    for (const PhotometricPoint& p : t.levels[l]) {
      const Eigen::Vector2d xn = p.p_r.head<2>() / p.p_r.z();
      const Eigen::Vector2d xd = lens.distort(xn);
      const double u = k.fx * xd.x() + k.cx, v = k.fy * xd.y() + k.cy;
      ASSERT_NEAR(u, std::round(u), 1e-9);
      ASSERT_NEAR(v, std::round(v), 1e-9);
      const cv::Mat& g = image.gray[l];
      const double value = l == 0 ? g.at<std::uint8_t>(cvRound(v), cvRound(u)) : g.at<float>(cvRound(v), cvRound(u));
      EXPECT_EQ(value, p.intensity);
      if (l == 0) farthest = std::max(farthest, std::hypot(k.fx * xn.x() + k.cx - u, k.fy * xn.y() + k.cy - v));
    }
  }
  EXPECT_GT(farthest, 3) << "the lens must move the pixels for this test to say anything";
}

TEST(PhotometricAlignment, OptionsAreChecked) {
  PhotometricOptions o;
  o.levels = 0;
  EXPECT_ANY_THROW(o.check());
  o = PhotometricOptions{};
  o.max_depth = 0.1;  // below min_depth
  EXPECT_ANY_THROW(o.check());
}

}  // namespace
}  // namespace amos::geometry
