// End-to-end checks of the generator: ground truth is exact (static pixels reproject within the noise model),
// masks are exactly the movers' visible geometry, and the same options give the same bytes.
#include "amos/synth/sequence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

namespace amos::synth {
namespace {

SequenceOptions quickSequence(const std::string& preset, int frames = 30, std::uint32_t seed = 3) {
  SequenceOptions o;
  o.preset = preset;
  o.seed = seed;
  o.frames = frames;
  o.metres_per_texel = 0.008;  // coarser textures: faster set-up, same geometry
  return o;
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * v.size()));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

float bilinear(const cv::Mat& m, double u, double v) {
  const int x = static_cast<int>(std::floor(u)), y = static_cast<int>(std::floor(v));
  const float fx = static_cast<float>(u - x), fy = static_cast<float>(v - y);
  return (1 - fx) * (1 - fy) * m.at<float>(y, x) + fx * (1 - fy) * m.at<float>(y, x + 1) +
         (1 - fx) * fy * m.at<float>(y + 1, x) + fx * fy * m.at<float>(y + 1, x + 1);
}

struct Reprojection {
  double consistent_fraction = 0;         // in-view static pixels whose predicted depth matches frame j
  std::vector<double> exact_error_m;      // |z predicted from exact depth - exact depth of j| (consistent pixels)
  std::vector<double> normalised_noise;   // measured-depth residual / sqrt(sigma_i^2 + sigma_j^2)
  std::vector<double> colour_difference;  // |grey_i - grey_j| at consistent pixels
};

// Moves every static pixel of frame i into frame j with the ground-truth poses (and an optional error on them).
Reprojection reproject(const SyntheticFrame& fi, const SyntheticFrame& fj, const core::CameraIntrinsics& k,
                       const DepthNoiseOptions& noise, const core::SE3& pose_error = core::SE3::Identity()) {
  const core::PinholeCamera cam(k);
  const core::SE3 T_ji = (fj.T_wc * pose_error).inverse() * fi.T_wc;
  cv::Mat gi, gj;
  cv::cvtColor(fi.bgr, gi, cv::COLOR_BGR2GRAY);
  cv::cvtColor(fj.bgr, gj, cv::COLOR_BGR2GRAY);
  gi.convertTo(gi, CV_32F);
  gj.convertTo(gj, CV_32F);
  Reprojection r;
  long in_view = 0, consistent = 0;
  for (int y = 0; y < k.height; y += 2)
    for (int x = 0; x < k.width; x += 2) {
      if (fi.mask.at<std::uint16_t>(y, x) != 0) continue;
      const double ze = fi.exact_depth.at<float>(y, x);
      if (!(ze > 0.4) || ze > 5.0) continue;
      const Eigen::Vector3d pe = T_ji * cam.backProject(x, y, ze);
      const Eigen::Vector2d uv = cam.project(pe);
      if (pe.z() <= 0.4 || !cam.inImage(uv.x(), uv.y(), 2)) continue;
      const int qx = static_cast<int>(std::lround(uv.x())), qy = static_cast<int>(std::lround(uv.y()));
      if (fj.mask.at<std::uint16_t>(qy, qx) != 0) continue;
      ++in_view;
      const double zj_exact = bilinear(fj.exact_depth, uv.x(), uv.y());
      const double err = std::abs(pe.z() - zj_exact);
      if (err > 0.01 + 0.01 * pe.z()) continue;  // occluded in j, or at a depth edge
      ++consistent;
      r.exact_error_m.push_back(err);
      r.colour_difference.push_back(std::abs(gi.at<float>(y, x) - bilinear(gj, uv.x(), uv.y())));
      const double zi = fi.depth.at<float>(y, x), zj = fj.depth.at<float>(qy, qx);
      if (zi <= 0 || zj <= 0) continue;
      // Predicted depth from the measured depth, compared with the measurement at the nearest pixel, corrected
      // by the exact depth difference between that pixel centre and the predicted sub-pixel position.
      const Eigen::Vector3d pm = T_ji * cam.backProject(x, y, zi);
      const double offset = fj.exact_depth.at<float>(qy, qx) - zj_exact;
      const double sigma = std::hypot(depthSigma(noise, ze), depthSigma(noise, pe.z()));
      r.normalised_noise.push_back((pm.z() - (zj - offset)) / sigma);
    }
  r.consistent_fraction = in_view ? static_cast<double>(consistent) / in_view : 0;
  return r;
}

TEST(Sequence, StaticPixelsReprojectWithinTheNoiseModel) {
  const SequenceGenerator gen(quickSequence("walking_xyz"));
  const SyntheticFrame f0 = gen.render(0), f1 = gen.render(20);
  // The camera really moved (xyz motion), so the test is not trivially passed by a still camera.
  EXPECT_GT(core::translationNorm(f0.T_wc.inverse() * f1.T_wc), 0.03);
  const Reprojection r = reproject(f0, f1, gen.intrinsics(), gen.options().sensor.depth);
  EXPECT_GT(r.consistent_fraction, 0.85);
  EXPECT_LT(median(r.exact_error_m), 0.001);
  ASSERT_GT(r.normalised_noise.size(), 10000u);
  // The measured residuals follow the noise model: robust sigma ~1, almost nothing beyond 5 sigma.
  std::vector<double> abs_noise;
  for (double v : r.normalised_noise) abs_noise.push_back(std::abs(v));
  const double robust_sigma = 1.4826 * median(abs_noise);
  EXPECT_GT(robust_sigma, 0.8);
  EXPECT_LT(robust_sigma, 1.3);
  EXPECT_LT(quantile(abs_noise, 0.99), 5.0);
  // Static surfaces keep their colour (world-fixed Lambertian lighting), up to noise and resampling.
  EXPECT_LT(median(r.colour_difference), 6);

  // Control: a 3 cm / 1 degree error in the pose breaks this, so the checks above can fail.
  core::Vector6d xi;
  xi << 0.03, 0.0, 0.03, 0.0, 1.0 * M_PI / 180, 0.0;
  const Reprojection bad = reproject(f0, f1, gen.intrinsics(), gen.options().sensor.depth, core::expSE3(xi));
  std::cout << "reprojection: consistent " << r.consistent_fraction << " exact error median " << median(r.exact_error_m)
            << " m, robust sigma " << robust_sigma << ", grey difference median " << median(r.colour_difference)
            << "; with a pose error: " << bad.consistent_fraction << ", " << median(bad.exact_error_m) << " m, "
            << median(bad.colour_difference) << "\n";
  EXPECT_GT(median(bad.exact_error_m), 0.01);
  EXPECT_GT(median(bad.colour_difference), median(r.colour_difference) + 3);
}

// Compares the full render with the movers alone and the room alone: mask pixel == id exactly where the mover's
// geometry is in front of the room.
struct MaskCheck {
  long mover_pixels = 0, hidden_mover_pixels = 0, mismatches = 0;
};

MaskCheck checkMasks(const SequenceGenerator& gen, int index) {
  const RenderedImage full = gen.renderExact(index, true, true, false);
  const RenderedImage room = gen.renderExact(index, true, false, false);
  const RenderedImage movers = gen.renderExact(index, false, true, false);
  const SyntheticFrame frame = gen.render(index);
  MaskCheck c;
  for (int y = 0; y < full.depth.rows; ++y)
    for (int x = 0; x < full.depth.cols; ++x) {
      const float zr = room.depth.at<float>(y, x), zm = movers.depth.at<float>(y, x);
      const bool mover_in_front = zm > 0 && (zr <= 0 || zm < zr);
      const std::uint16_t expected = mover_in_front ? movers.instance.at<std::uint16_t>(y, x) : 0;
      const float expected_z = mover_in_front ? zm : zr;
      if (full.instance.at<std::uint16_t>(y, x) != expected || frame.mask.at<std::uint16_t>(y, x) != expected ||
          full.depth.at<float>(y, x) != expected_z || frame.exact_depth.at<float>(y, x) != expected_z)
        ++c.mismatches;
      if (expected) ++c.mover_pixels;
      if (zm > 0 && !mover_in_front) ++c.hidden_mover_pixels;
    }
  return c;
}

TEST(Sequence, MasksAreExactlyTheMoversVisibleGeometryBothWaysRoundOcclusions) {
  // Walkers cross in front of the desk; seated people are hidden by the desk below the chest.
  for (const char* preset : {"walking_xyz", "sitting_xyz", "objects_xyz"}) {
    const SequenceGenerator gen(quickSequence(preset, 300));
    long movers = 0, hidden = 0;
    for (int index : {40, 130, 220}) {
      const MaskCheck c = checkMasks(gen, index);
      EXPECT_EQ(c.mismatches, 0) << preset << " frame " << index;
      movers += c.mover_pixels;
      hidden += c.hidden_mover_pixels;
    }
    EXPECT_GT(movers, 5000) << preset;  // movers are in view
    EXPECT_GT(hidden, 500) << preset;   // and the room hides parts of them
  }
}

TEST(Sequence, EveryMoverShowsUpAndMovesInItsPreset) {
  for (const char* preset : {"walking_static", "sitting_xyz", "box_push", "objects_xyz"}) {
    const SequenceGenerator gen(quickSequence(preset, 300));
    std::vector<long> seen(gen.instances().size() + 1, 0), moving(gen.instances().size() + 1, 0);
    for (int index = 0; index < gen.frameCount(); index += 30) {
      const cv::Mat mask = gen.renderExact(index, true, true, false).instance;
      for (int y = 0; y < mask.rows; y += 2)
        for (int x = 0; x < mask.cols; x += 2) ++seen[mask.at<std::uint16_t>(y, x)];
      for (std::uint16_t id : gen.movingInstances(gen.time(index))) ++moving[id];
    }
    for (const InstanceInfo& info : gen.instances()) {
      EXPECT_GT(seen[info.id], 200) << preset << " " << info.name;
      EXPECT_GT(moving[info.id], 2) << preset << " " << info.name;
    }
  }
}

// Movers that change state (issue 16): per phase, which instances move, and that each is in view and in the mask
// (at rest too: the mask holds every instance; the truth of a frame is the subset that moves).
TEST(Sequence, StateChangingMoversMoveOnlyInTheirPhase) {
  struct Phase {
    int frame;
    std::vector<std::string> moving;  // instance names moving at that frame
  };
  const std::vector<std::pair<std::string, std::vector<Phase>>> cases = {
      {"box_starts", {{30, {}}, {110, {}}, {150, {"box_starting"}}, {240, {"box_starting"}}, {290, {}}}},
      {"box_stops", {{30, {"box_stopping"}}, {90, {"box_stopping"}}, {130, {}}, {280, {}}}},
      {"chair_push", {{30, {}}, {80, {}}, {120, {"chair_pusher", "pushed_chair"}}, {270, {}}}},
  };
  for (const auto& [preset, phases] : cases) {
    const SequenceGenerator gen(quickSequence(preset, 300));
    EXPECT_EQ(gen.preset().static_counterpart, "static_xyz") << preset;
    for (const Phase& phase : phases) {
      std::vector<std::string> moving;
      for (std::uint16_t id : gen.movingInstances(gen.time(phase.frame)))
        for (const InstanceInfo& info : gen.instances())
          if (info.id == id) moving.push_back(info.name);
      EXPECT_EQ(moving, phase.moving) << preset << " frame " << phase.frame;
      const cv::Mat mask = gen.renderExact(phase.frame, true, true, false).instance;
      for (const InstanceInfo& info : gen.instances())
        EXPECT_GT(cv::countNonZero(mask == info.id), 500) << preset << " " << info.name << " frame " << phase.frame;
      const MaskCheck c = checkMasks(gen, phase.frame);
      EXPECT_EQ(c.mismatches, 0) << preset << " frame " << phase.frame;
    }
  }
  // The person is a prior class, the chair it pushes is not.
  const SequenceGenerator gen(quickSequence("chair_push", 30));
  ASSERT_EQ(gen.instances().size(), 2u);
  EXPECT_EQ(gen.instances()[0].category, "person");
  EXPECT_EQ(gen.instances()[1].category, "object");
  EXPECT_NE(gen.instances()[0].id, gen.instances()[1].id);
}

TEST(Sequence, StaticCounterpartFliesTheSamePathThroughTheSameRoom) {
  for (const Preset& p : allPresets()) {
    if (p.static_counterpart.find(' ') != std::string::npos) continue;  // "X --no-movers"
    EXPECT_EQ(findPreset(p.static_counterpart).motion, p.motion) << p.name;
    EXPECT_TRUE(findPreset(p.static_counterpart).movers.empty()) << p.name;
  }
  SequenceOptions dynamic = quickSequence("box_push", 30), counterpart = quickSequence("static_xyz", 30), removed = dynamic;
  removed.movers = false;
  const SequenceGenerator a(dynamic), b(counterpart), c(removed);
  for (int index : {0, 17, 29}) {
    EXPECT_TRUE(a.poseWc(index).isApprox(b.poseWc(index), 0)) << index;
    EXPECT_TRUE(a.poseWc(index).isApprox(c.poseWc(index), 0)) << index;
  }
  const SyntheticFrame fb = b.render(12), fc = c.render(12);
  EXPECT_EQ(cv::norm(fb.bgr, fc.bgr, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(fb.depth_raw, fc.depth_raw, cv::NORM_INF), 0);
  EXPECT_EQ(cv::countNonZero(fb.mask), 0);
}

TEST(Sequence, FramesAreIndependentAndSeedsMatter) {
  const SequenceGenerator gen(quickSequence("walking_xyz", 30));
  const SyntheticFrame a = gen.render(7);
  gen.render(3);
  const SyntheticFrame b = gen.render(7);
  EXPECT_EQ(cv::norm(a.bgr, b.bgr, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(a.depth_raw, b.depth_raw, cv::NORM_INF), 0);
  const SequenceGenerator other(quickSequence("walking_xyz", 30, 4));
  EXPECT_GT(cv::norm(a.bgr, other.render(7).bgr, cv::NORM_L1), 0);
  EXPECT_FALSE(gen.poseWc(7).isApprox(other.poseWc(7), 1e-6));
}

TEST(Sequence, MotionBlurSmearsColourOnlyWhereThingsMove) {
  SequenceOptions sharp = quickSequence("walking_static", 300), blurred = sharp;
  blurred.sensor.motion_blur = true;
  blurred.sensor.exposure_s = 0.03;
  const SequenceGenerator a(sharp), b(blurred);
  int index = 0;  // a frame where a walker is well in view
  for (; index < 300; index += 15)
    if (cv::countNonZero(a.renderExact(index, true, true, false).instance) > 20000) break;
  ASSERT_LT(index, 300);
  const SyntheticFrame fa = a.render(index), fb = b.render(index);
  EXPECT_EQ(cv::norm(fa.mask, fb.mask, cv::NORM_INF), 0);  // ground truth stays at mid-exposure
  EXPECT_EQ(cv::norm(fa.exact_depth, fb.exact_depth, cv::NORM_INF), 0);
  cv::Mat diff;
  cv::absdiff(fa.bgr, fb.bgr, diff);
  cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
  cv::Mat mover = fa.mask > 0, still = fa.mask == 0;
  cv::erode(still, still, cv::Mat::ones(15, 15, CV_8U));  // away from the movers' smeared outlines
  // The almost-still camera blurs the room a little; the walking people a lot more.
  EXPECT_GT(cv::mean(diff, mover)[0], 2 * cv::mean(diff, still)[0]);
}

TEST(Sequence, LoopIsTrackableEverywhere) {
  // ORB-SLAM needs corners all over every view, walls at a few metres and depth on most of the image.
  SequenceOptions o = quickSequence("static_loop", 0);
  o.metres_per_texel = 0.004;  // the real texture resolution: this is about texture
  const SequenceGenerator gen(o);
  EXPECT_GE(gen.frameCount(), 600);
  for (int index = 0; index < gen.frameCount(); index += 40) {
    const SyntheticFrame f = gen.render(index);
    cv::Mat grey;
    cv::cvtColor(f.bgr, grey, cv::COLOR_BGR2GRAY);
    std::vector<cv::KeyPoint> corners;
    cv::FAST(grey, corners, 20, true);
    int cells[4][4] = {};
    for (const cv::KeyPoint& kp : corners)
      ++cells[static_cast<int>(kp.pt.y) * 4 / grey.rows][static_cast<int>(kp.pt.x) * 4 / grey.cols];
    int good_cells = 0;
    for (auto& row : cells)
      for (int n : row) good_cells += n >= 10;
    EXPECT_GT(corners.size(), 500u) << "frame " << index;
    EXPECT_GE(good_cells, 13) << "frame " << index;
    std::vector<double> depths;
    for (int y = 0; y < f.depth.rows; y += 4)
      for (int x = 0; x < f.depth.cols; x += 4)
        if (f.depth.at<float>(y, x) > 0) depths.push_back(f.depth.at<float>(y, x));
    EXPECT_GT(depths.size(), 0.85 * (f.depth.rows / 4) * (f.depth.cols / 4)) << "frame " << index;
    EXPECT_GT(median(depths), 1.0) << "frame " << index;
    EXPECT_LT(median(depths), 4.0) << "frame " << index;
  }
}

}  // namespace
}  // namespace amos::synth
