#include "amos/testing/synthetic_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"

namespace amos::testing {

namespace {

// Uniform noise smoothed by a Gaussian of sigma texels, zero mean and unit deviation (CV_32F). Wide blurs are done
// on a coarser grid and scaled up (the scenes are built in every test: this keeps a room's textures at ~0.1 s).
cv::Mat smoothNoise(cv::RNG& rng, cv::Size size, double sigma) {
  const int factor = std::max(1, static_cast<int>(sigma / 2));
  cv::Mat n(cv::Size(size.width / factor + 2, size.height / factor + 2), CV_32F);
  rng.fill(n, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(n, n, cv::Size(0, 0), sigma / factor);
  if (factor > 1) {
    cv::resize(n, n, cv::Size(n.cols * factor, n.rows * factor), 0, 0, cv::INTER_LINEAR);
  }
  n = n(cv::Rect(0, 0, size.width, size.height)).clone();
  cv::Scalar mean, dev;
  cv::meanStdDev(n, mean, dev);
  n = (n - mean[0]) / std::max(dev[0], 1e-9);
  return n;
}

cv::Mat toBgr(const cv::Mat& image) {
  core::require(!image.empty() && (image.type() == CV_8UC3 || image.type() == CV_8UC1),
                "SyntheticScene: a texture must be a non-empty CV_8UC3 or CV_8UC1 image");
  if (image.type() == CV_8UC3) return image;
  cv::Mat bgr;
  cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

synth::Surface surfaceOf(int texture) {
  synth::Surface s;
  s.texture = texture;
  return s;
}

synth::Quad quadOf(const Eigen::Vector3d& origin, const Eigen::Vector3d& edge_u, const Eigen::Vector3d& edge_v,
                   int texture, std::uint16_t instance) {
  core::require(std::abs(edge_u.normalized().dot(edge_v.normalized())) < 1e-9,
                "SyntheticScene: a rectangle's edges must be perpendicular");
  synth::Quad q;
  q.origin = origin;
  q.edge_u = edge_u;
  q.edge_v = edge_v;
  q.surface = surfaceOf(texture);
  q.instance = instance;
  return q;
}

// Distance from p to the rectangle origin + a * u + b * v, a, b in [0, 1] (u perpendicular to v).
double distanceToRectangle(const synth::Quad& q, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - q.origin;
  const double a = std::clamp(d.dot(q.edge_u) / q.edge_u.squaredNorm(), 0.0, 1.0);
  const double b = std::clamp(d.dot(q.edge_v) / q.edge_v.squaredNorm(), 0.0, 1.0);
  return (p - (q.origin + a * q.edge_u + b * q.edge_v)).norm();
}

}  // namespace

cv::Mat noiseTexture(std::uint32_t seed, cv::Size size) {
  cv::RNG rng(0x9e3779b9u ^ seed);
  // Three octaves: fine grain for the lower pyramid levels and close views, blobs for the upper ones and far views.
  cv::Mat sum = smoothNoise(rng, size, 1.2) + 0.8 * smoothNoise(rng, size, 4.0) + 0.8 * smoothNoise(rng, size, 12.0);
  cv::Mat out;
  sum.convertTo(out, CV_8U, 45.0, 128.0);
  return out;
}

cv::Mat fineNoiseTexture(std::uint32_t seed, cv::Size size, double blur_texels) {
  cv::RNG rng(seed);
  cv::Mat t(size, CV_8U);
  rng.fill(t, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(t, t, cv::Size(0, 0), blur_texels);
  cv::normalize(t, t, 0, 255, cv::NORM_MINMAX);
  return t;
}

SyntheticScene::SyntheticScene(const core::CameraIntrinsics& intrinsics) : renderer_(intrinsics) {}

int SyntheticScene::addTexture(const cv::Mat& image, bool mipmaps) {
  return textures_.add(synth::Texture(toBgr(image), cv::Mat(), false, mipmaps));
}

void SyntheticScene::addRectangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& edge_u,
                                  const Eigen::Vector3d& edge_v, int texture) {
  static_.quads.push_back(quadOf(origin, edge_u, edge_v, texture, 0));
}

void SyntheticScene::addBox(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& max_corner, int texture) {
  static_.addBox(min_corner, max_corner, synth::allFaces(surfaceOf(texture)));
}

std::uint16_t SyntheticScene::addMovingRectangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& edge_u,
                                                 const Eigen::Vector3d& edge_v, int texture) {
  const auto id = static_cast<std::uint16_t>(movers_.size() + 1);
  synth::SceneGeometry g;
  g.quads.push_back(quadOf(origin, edge_u, edge_v, texture, id));
  movers_.push_back(std::move(g));
  return id;
}

std::uint16_t SyntheticScene::addMovingBox(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& max_corner,
                                           int texture) {
  const auto id = static_cast<std::uint16_t>(movers_.size() + 1);
  synth::SceneGeometry g;
  g.addBox(min_corner, max_corner, synth::allFaces(surfaceOf(texture)), id);
  movers_.push_back(std::move(g));
  return id;
}

SyntheticView SyntheticScene::render(const core::SE3& T_cw, const std::vector<core::SE3>& mover_motion) const {
  std::vector<synth::SceneGeometry> moved;
  moved.reserve(movers_.size());
  for (std::size_t i = 0; i < movers_.size(); ++i) {
    moved.push_back(i < mover_motion.size() ? synth::transformed(movers_[i], mover_motion[i]) : movers_[i]);
  }
  std::vector<const synth::SceneGeometry*> parts{&static_};
  for (const auto& g : moved) parts.push_back(&g);
  synth::Lighting flat;
  flat.ambient = 1.0;  // the texture's own grey values, from every viewpoint
  const synth::RenderedImage image = renderer_.render(parts, textures_, flat, T_cw, true);

  SyntheticView view;
  view.T_cw = T_cw;
  image.color.convertTo(view.bgr, CV_8UC3);
  cv::cvtColor(view.bgr, view.gray, cv::COLOR_BGR2GRAY);
  view.depth = image.depth;
  view.instance = image.instance;
  view.mover_mask = image.instance > 0;
  return view;
}

double SyntheticScene::distanceToStaticSurface(const Eigen::Vector3d& p_w) const {
  double best = std::numeric_limits<double>::infinity();
  for (const synth::Quad& q : static_.quads) best = std::min(best, distanceToRectangle(q, p_w));
  return best;
}

SyntheticScene texturedRoom(const core::CameraIntrinsics& intrinsics, std::uint32_t seed) {
  SyntheticScene scene(intrinsics);
  using V = Eigen::Vector3d;
  // Room: x in [-2, 2], y in [-1.4, 1.0] (ceiling above, floor below: y is down), z in [-1.5, 4.5].
  const double x0 = -2, x1 = 2, y0 = -1.4, y1 = 1.0, z0 = -1.5, z1 = 4.5;
  constexpr double kTexelsPerMetre = 200;  // 5 mm texels: about one per pixel at 2.7 m with f = 535
  auto texture = [&](std::uint32_t k, double width_m, double height_m) {
    return scene.addTexture(noiseTexture(seed * 16 + k, cv::Size(static_cast<int>(width_m * kTexelsPerMetre),
                                                                  static_cast<int>(height_m * kTexelsPerMetre))));
  };
  const double W = x1 - x0, H = y1 - y0, D = z1 - z0;
  scene.addRectangle(V(x0, y0, z1), V(W, 0, 0), V(0, H, 0), texture(0, W, H));   // front wall
  scene.addRectangle(V(x1, y0, z0), V(0, 0, D), V(0, H, 0), texture(1, D, H));   // right wall
  scene.addRectangle(V(x0, y0, z0), V(0, 0, D), V(0, H, 0), texture(2, D, H));   // left wall
  scene.addRectangle(V(x0, y0, z0), V(W, 0, 0), V(0, H, 0), texture(3, W, H));   // back wall
  scene.addRectangle(V(x0, y1, z0), V(W, 0, 0), V(0, 0, D), texture(4, W, D));   // floor
  scene.addRectangle(V(x0, y0, z0), V(W, 0, 0), V(0, 0, D), texture(5, W, D));   // ceiling
  // Structure at several depths, so that a moving camera sees parallax.
  scene.addBox(V(-1.2, 0.2, 2.2), V(-0.4, 1.0, 3.0), texture(6, 0.8, 0.8));  // a crate on the floor, left
  scene.addBox(V(0.5, -0.3, 2.6), V(1.3, 1.0, 3.3), texture(7, 0.8, 1.3));   // a cabinet, right
  scene.addBox(V(0.1, -1.4, 1.4), V(0.35, 1.0, 1.65), texture(8, 0.25, 2.4));  // a pillar, near
  return scene;
}

SyntheticScene crateScene(const core::CameraIntrinsics& intrinsics) {
  SyntheticScene scene(intrinsics);
  using V = Eigen::Vector3d;
  // The textures and texel scales of the front end's first tests (350 texels per metre on the wall and the floor,
  // 500 to 1500 on the crate, the pillar and the box), sampled bilinearly at full resolution as their ray caster
  // did: the aliased fine grain is what the front end's corner tracking and superpixels were tuned on. That caster
  // put texel k at texture coordinate k, synth::Texture puts it at k + 0.5: the wall and the floor, whose edges are
  // out of view or hidden, start half a texel early (1.4 mm) so that their pixels sample the same texture values
  // as before; the small objects keep their exact outlines (their textures move by a fifth of a pixel or less).
  auto texture = [&](const cv::Mat& image) { return scene.addTexture(image, /*mipmaps=*/false); };
  auto rectangle = [&](V origin, const V& edge_u, const V& edge_v, double texels_per_m_u, double texels_per_m_v,
                       int tex, bool moving = false) {
    if (texels_per_m_u > 0) {
      origin -= 0.5 / texels_per_m_u * edge_u.normalized() + 0.5 / texels_per_m_v * edge_v.normalized();
    }
    if (moving) {
      scene.addMovingRectangle(origin, edge_u, edge_v, tex);
    } else {
      scene.addRectangle(origin, edge_u, edge_v, tex);
    }
  };
  const cv::Mat crate = fineNoiseTexture(4, cv::Size(400, 400), 1.5);
  rectangle(V(-2.0, -1.5, 3.0), V(4.0, 0, 0), V(0, 4.0, 0), 350, 350,
            texture(fineNoiseTexture(1, {1400, 1400}, 1.5)));  // wall
  rectangle(V(-2.0, 0.7, 0.0), V(4.0, 0, 0), V(0, 0, 3.0), 350, 350,
            texture(fineNoiseTexture(3, {1400, 1400}, 1.5)(cv::Rect(0, 0, 1400, 1050))));  // floor
  rectangle(V(0.3, -0.5, 2.0), V(0.5, 0, 0), V(0, 0.7, 0), 0, 0, texture(crate(cv::Rect(0, 0, 350, 350))));
  rectangle(V(0.25, -0.4, 1.0), V(0.15, 0, 0), V(0, 0.9, 0), 0, 0,
            texture(crate(cv::Rect(0, 0, 225, 360))));  // pillar
  rectangle(V(-0.4, -0.2, 1.5), V(0.4, 0, 0), V(0, 0.5, 0), 0, 0,
            texture(fineNoiseTexture(2, {400, 400}, 1.5)(cv::Rect(0, 0, 320, 350))), /*moving=*/true);  // box
  return scene;
}

core::SE3 translation(const Eigen::Vector3d& t) {
  core::SE3 T = core::SE3::Identity();
  T.translation() = t;
  return T;
}

std::vector<core::SE3> constantVelocityPath(int frames, const core::Vector6d& twist_wc, const core::SE3& T_wc_first) {
  std::vector<core::SE3> path;
  path.reserve(static_cast<std::size_t>(std::max(frames, 0)));
  for (int i = 0; i < frames; ++i) path.push_back((core::expSE3(i * twist_wc) * T_wc_first).inverse());
  return path;
}

std::vector<core::SE3> swayPath(int frames, double amplitude_m, double amplitude_rad, double period_frames) {
  std::vector<core::SE3> path;
  const double w = 2 * M_PI / period_frames;
  const double phase[6] = {0.0, 1.3, 2.1, 0.7, 2.9, 4.2};
  for (int i = 0; i < frames; ++i) {
    core::Vector6d xi;
    for (int k = 0; k < 6; ++k) {
      const double amplitude = k < 3 ? amplitude_m : amplitude_rad;
      xi[k] = amplitude * (std::sin(w * i + phase[k]) - std::sin(phase[k]));  // 0 at frame 0
    }
    path.push_back(core::expSE3(xi).inverse());
  }
  return path;
}

SyntheticSequence::SyntheticSequence(std::shared_ptr<const SyntheticScene> scene, std::vector<core::SE3> T_cw,
                                     double fps, MoverMotion movers)
    : scene_(std::move(scene)), T_cw_(std::move(T_cw)), fps_(fps), movers_(std::move(movers)) {
  core::require(scene_ != nullptr, "SyntheticSequence: no scene");
  core::require(fps_ > 0, "SyntheticSequence: fps must be positive");
}

SyntheticView SyntheticSequence::view(int i) const {
  return scene_->render(T_cw(i), movers_ ? movers_(i) : std::vector<core::SE3>{});
}

io::RgbdFrame SyntheticSequence::rgbdFrame(int i) const { return toRgbdFrame(view(i), i, timestamp(i)); }

io::RgbdFrame SyntheticSequence::toRgbdFrame(const SyntheticView& view, int index, double timestamp) {
  io::RgbdFrame f;
  f.index = static_cast<std::size_t>(index);
  f.timestamp = timestamp;
  f.bgr = view.bgr;
  f.depth = view.depth;
  return f;
}

}  // namespace amos::testing
