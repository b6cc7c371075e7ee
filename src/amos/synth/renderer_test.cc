#include "amos/synth/renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include "amos/testing/test_camera.h"

namespace amos::synth {
namespace {

// The camera of the synthetic sequences (TUM fr3); the expected extents below are worked out for it.
core::CameraIntrinsics tumFr3() { return testing::testIntrinsics(); }

// Camera at the world origin looking along world +z (T_cw = identity).
const core::SE3 kIdentity = core::SE3::Identity();

TEST(Renderer, FrontoParallelQuadHasExactDepthAndProjectedExtent) {
  SceneGeometry g;
  Quad q;
  q.origin = {-0.5, -0.25, 2.0};
  q.edge_u = {1.0, 0, 0};
  q.edge_v = {0, 0.5, 0};
  q.instance = 7;
  g.quads.push_back(q);
  const Renderer r(tumFr3());
  const RenderedImage img = r.render({&g}, TextureBank(), Lighting(), kIdentity, false);
  const auto k = tumFr3();
  int covered = 0;
  for (int y = 0; y < k.height; ++y)
    for (int x = 0; x < k.width; ++x) {
      const double X = (x - k.cx) / k.fx * 2.0, Y = (y - k.cy) / k.fy * 2.0;
      const bool inside = X >= -0.5 && X <= 0.5 && Y >= -0.25 && Y <= 0.25;
      const float z = img.depth.at<float>(y, x);
      ASSERT_EQ(inside, z > 0) << x << "," << y;
      if (inside) {
        EXPECT_NEAR(z, 2.0, 1e-6);
        EXPECT_EQ(img.instance.at<std::uint16_t>(y, x), 7);
        EXPECT_NEAR(img.incidence.at<float>(y, x), 1.0 / std::hypot(1.0, std::hypot(X / 2, Y / 2)), 1e-5);
        ++covered;
      }
    }
  // 1 m x 0.5 m at 2 m: about (535.4 / 2) x (539.2 / 4) pixels.
  EXPECT_NEAR(covered, 267.7 * 134.8, 300);
}

TEST(Renderer, NearerPrimitiveWinsWhateverTheDrawingOrder) {
  SceneGeometry back, front;
  back.addBox(Eigen::Vector3d(-1, -1, 3), Eigen::Vector3d(1, 1, 3.2), allFaces(Surface()), 1);
  front.addSphere(Eigen::Vector3d(0, 0, 2), 0.3, Surface(), 2);
  const Renderer r(tumFr3());
  for (const auto& parts :
       {std::vector<const SceneGeometry*>{&back, &front}, std::vector<const SceneGeometry*>{&front, &back}}) {
    const RenderedImage img = r.render(parts, TextureBank(), Lighting(), kIdentity, false);
    // The sphere's nearest point lies on the optical axis.
    const int cx = 320, cy = 248;
    EXPECT_EQ(img.instance.at<std::uint16_t>(cy, cx), 2);
    const double x = (cx - 320.1) / 535.4, y = (cy - 247.6) / 539.2;
    // Exact ray-sphere intersection through that pixel.
    const double A = x * x + y * y + 1, B = -4, C = 4 - 0.09;
    EXPECT_NEAR(img.depth.at<float>(cy, cx), (-B - std::sqrt(B * B - 4 * A * C)) / (2 * A), 1e-5);
    EXPECT_EQ(img.instance.at<std::uint16_t>(180, 250), 1);
    EXPECT_NEAR(img.depth.at<float>(180, 250), 3.0, 1e-5);
  }
}

TEST(Renderer, CylinderSilhouetteMatchesItsProjection) {
  SceneGeometry g;
  // Upright cylinder (along camera -y), radius 0.2, 1 m long, 2.5 m ahead.
  g.addCylinder(Eigen::Vector3d(0, 0.5, 2.5), Eigen::Vector3d(0, -0.5, 2.5), 0.2, Surface(), 3);
  const Renderer r(tumFr3());
  const RenderedImage img = r.render({&g}, TextureBank(), Lighting(), kIdentity, false);
  // On the image row through the axis' centre, the silhouette half-width is f * r / sqrt(d^2 - r^2).
  const int y = 248;
  int first = -1, last = -1;
  for (int x = 0; x < 640; ++x)
    if (img.instance.at<std::uint16_t>(y, x) == 3) {
      if (first < 0) first = x;
      last = x;
    }
  const double half = 535.4 * 0.2 / std::sqrt(2.5 * 2.5 - 0.04);
  EXPECT_NEAR(last - first + 1, 2 * half, 2.0);
  EXPECT_NEAR(img.depth.at<float>(y, 320), 2.3, 1e-3);
}

TEST(Renderer, BackFacesOfBoxesAreCulledButBoxStillOpaque) {
  SceneGeometry g;
  g.addBox(Eigen::Vector3d(-0.3, -0.3, 1.7), Eigen::Vector3d(0.3, 0.3, 2.3), allFaces(Surface()), 5);
  const Renderer r(tumFr3());
  const RenderedImage img = r.render({&g}, TextureBank(), Lighting(), kIdentity, false);
  EXPECT_NEAR(img.depth.at<float>(248, 320), 1.7, 1e-6);
}

TEST(Renderer, TexturedQuadShowsItsTextureUpright) {
  // A 2 x 2 texture: top row red | green, bottom row blue | white, on a quad 2 m ahead, no lights.
  cv::Mat img(2, 2, CV_8UC3);
  img.at<cv::Vec3b>(0, 0) = {0, 0, 200};
  img.at<cv::Vec3b>(0, 1) = {0, 200, 0};
  img.at<cv::Vec3b>(1, 0) = {200, 0, 0};
  img.at<cv::Vec3b>(1, 1) = {200, 200, 200};
  TextureBank bank;
  SceneGeometry g;
  Quad q;
  q.origin = {-0.5, -0.5, 2.0};  // top-left (camera y points down)
  q.edge_u = {1.0, 0, 0};
  q.edge_v = {0, 1.0, 0};
  q.surface.texture = bank.add(Texture(img));
  g.quads.push_back(q);
  Lighting flat;
  flat.ambient = 1.0;
  const RenderedImage out = Renderer(tumFr3()).render({&g}, bank, flat, kIdentity, true);
  auto at = [&](double X, double Y) {  // colour where the point (X, Y, 2) projects
    return out.color.at<cv::Vec3f>(static_cast<int>(std::lround(539.2 * Y / 2 + 247.6)),
                                   static_cast<int>(std::lround(535.4 * X / 2 + 320.1)));
  };
  EXPECT_NEAR(at(-0.4, -0.4)[2], 200, 1);  // red, top left
  EXPECT_NEAR(at(0.4, -0.4)[1], 200, 1);   // green, top right
  EXPECT_NEAR(at(-0.4, 0.4)[0], 200, 1);   // blue, bottom left
  EXPECT_NEAR(at(0.4, 0.4)[0] + at(0.4, 0.4)[1] + at(0.4, 0.4)[2], 600, 3);
}

TEST(Texture, MipLevelsAverageAndAlphaCuts) {
  cv::Mat checker(64, 64, CV_8UC3);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      checker.at<cv::Vec3b>(y, x) = ((x + y) % 2) ? cv::Vec3b(255, 255, 255) : cv::Vec3b(0, 0, 0);
  cv::Mat alpha(64, 64, CV_8UC1, cv::Scalar(0));
  alpha(cv::Rect(0, 0, 32, 64)).setTo(255);
  const Texture t(checker, alpha, true);
  EXPECT_GT(t.levelCount(), 3);
  // Far away (many texels per pixel) the checker averages to grey.
  EXPECT_NEAR(t.sample(0.3, 0.7, 4.0)[0], 127.5, 2);
  EXPECT_NEAR(t.alpha(0.2, 0.5), 1.0, 1e-6);
  EXPECT_NEAR(t.alpha(0.8, 0.5), 0.0, 1e-6);
  // Repeat wraps: s and s + 3 sample the same texel.
  EXPECT_EQ(t.sample(0.123, 0.456, 0), t.sample(3.123, 0.456, 0));
}

// Without mipmaps a texture is sampled at full resolution however far away (the test scenes that must look as a
// plain ray caster's); with them a far checkerboard is its mean grey.
TEST(Texture, WithoutMipmapsSamplesTheFullResolutionAtAnyDistance) {
  cv::Mat checker(8, 8, CV_8UC3);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) checker.at<cv::Vec3b>(y, x) = cv::Vec3b::all((x + y) % 2 ? 255 : 0);
  const Texture mipmapped(checker), plain(checker, cv::Mat(), false, /*mipmaps=*/false);
  EXPECT_GT(mipmapped.levelCount(), 1);
  EXPECT_EQ(plain.levelCount(), 1);
  const double s = 0.5 / 8, t = 0.5 / 8;  // the centre of texel (0, 0), black
  EXPECT_NEAR(mipmapped.sample(s, t, 3.0)[0], 127.5, 1.0);
  EXPECT_FLOAT_EQ(plain.sample(s, t, 3.0)[0], 0.0f);
  EXPECT_FLOAT_EQ(plain.sample(s, t, 0.0)[0], mipmapped.sample(s, t, 0.0)[0]);
}

}  // namespace
}  // namespace amos::synth
