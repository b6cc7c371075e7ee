// The sensor effects one at a time, against exact renders (sensor_model.h): depth noise and colour noise apart,
// disparity steps, the depth image's time offset and the colour image's rolling shutter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "amos/core/error.h"
#include "amos/synth/sequence.h"
#include "amos/synth/tum_writer.h"
#include "amos/testing/scratch_dir.h"

namespace amos::synth {
namespace {

SequenceOptions quick(const std::string& preset, int frames = 12, std::uint32_t seed = 2) {
  SequenceOptions o;
  o.preset = preset;
  o.seed = seed;
  o.frames = frames;
  o.metres_per_texel = 0.008;  // coarser textures: faster set-up, same geometry
  return o;
}

// What the sensor delivers of an exact colour render when the colour noise is off: rounded to 8 bits.
cv::Mat eightBit(const cv::Mat& color) {
  cv::Mat out;
  color.convertTo(out, CV_8UC3);
  return out;
}

double maxDifference(const cv::Mat& a, const cv::Mat& b) { return cv::norm(a, b, cv::NORM_INF); }

TEST(SensorEffects, BandsOfOnePoseStackToTheWholeImage) {
  // A still camera under a rolling shutter: every band rendered at the same pose gives the global-shutter image.
  const SequenceGenerator gen(quick("walking_xyz"));
  const double t = 0.2;
  const RenderedImage whole = gen.renderExactAt(t, true, true, true);
  for (int rows : {1, 7, 8, 480}) {
    SensorOptions o;
    o.rolling_shutter_s = 1e-9;
    o.rolling_shutter_band_rows = rows;
    for (const ExposureBand& b : exposureBands(o, t)) {
      const RenderedImage part = gen.renderExactAt(t, true, true, true, {b.begin, b.end});
      const cv::Range r(b.begin, b.end);
      ASSERT_EQ(part.depth.rows, b.end - b.begin);
      EXPECT_EQ(maxDifference(part.color, whole.color.rowRange(r)), 0) << rows << " " << b.begin;
      EXPECT_EQ(maxDifference(part.depth, whole.depth.rowRange(r)), 0) << rows << " " << b.begin;
      EXPECT_EQ(maxDifference(part.instance, whole.instance.rowRange(r)), 0) << rows << " " << b.begin;
      EXPECT_EQ(maxDifference(part.incidence, whole.incidence.rowRange(r)), 0) << rows << " " << b.begin;
    }
  }
}

TEST(SensorEffects, ExposureBandsFollowTheReadout) {
  SensorOptions o;
  const std::vector<ExposureBand> global = exposureBands(o, 1.0);
  ASSERT_EQ(global.size(), 1u);
  EXPECT_EQ(global[0].begin, 0);
  EXPECT_EQ(global[0].end, 480);
  EXPECT_EQ(global[0].t, 1.0);
  o.rolling_shutter_s = 0.024;
  o.rolling_shutter_band_rows = 1;
  const std::vector<ExposureBand> rows = exposureBands(o, 1.0);
  ASSERT_EQ(rows.size(), 480u);
  for (int r : {0, 100, 240, 479}) EXPECT_NEAR(rows[r].t, 1.0 + (r / 480.0 - 0.5) * 0.024, 1e-12) << r;
  o.rolling_shutter_band_rows = 7;  // the last band is shorter
  const std::vector<ExposureBand> bands = exposureBands(o, 1.0);
  ASSERT_EQ(bands.size(), 69u);
  EXPECT_EQ(bands.back().begin, 476);
  EXPECT_EQ(bands.back().end, 480);
  EXPECT_NEAR(bands.back().t, 1.0 + (477.5 / 480 - 0.5) * 0.024, 1e-12);
}

TEST(SensorEffects, RollingShutterRendersEachBandAtItsTimeAndKeepsTheGroundTruth) {
  SequenceOptions o = quick("walking_halfsphere");
  o.sensor.color.enabled = false;
  SequenceOptions rolling = o;
  rolling.sensor.rolling_shutter_s = 0.025;
  rolling.sensor.rolling_shutter_band_rows = 16;
  const SequenceGenerator gen(o), gen_rs(rolling);
  const int k = 9;
  const SyntheticFrame global = gen.render(k), rs = gen_rs.render(k);
  EXPECT_TRUE(rs.T_wc.isApprox(global.T_wc, 0));  // the pose at the colour time stamp
  EXPECT_EQ(rs.timestamp, global.timestamp);
  EXPECT_EQ(rs.depth_timestamp, global.depth_timestamp);
  // Depth is a global-shutter image at the time stamp: unchanged.
  EXPECT_EQ(maxDifference(rs.depth_raw, global.depth_raw), 0);
  const double t = gen.time(k);
  for (const ExposureBand& b : exposureBands(rolling.sensor, t)) {
    const RenderedImage exact = gen.renderExactAt(b.t, true, true, true, {b.begin, b.end});
    const cv::Range r(b.begin, b.end);
    ASSERT_EQ(maxDifference(rs.bgr.rowRange(r), eightBit(exact.color)), 0) << b.begin;
    ASSERT_EQ(maxDifference(rs.mask.rowRange(r), exact.instance), 0) << b.begin;
  }
  // The camera moves: the top and bottom of the image differ from the global-shutter frame.
  EXPECT_GT(cv::norm(rs.bgr.rowRange(0, 16), global.bgr.rowRange(0, 16), cv::NORM_L1), 0);
  EXPECT_GT(cv::norm(rs.bgr.rowRange(464, 480), global.bgr.rowRange(464, 480), cv::NORM_L1), 0);
}

TEST(SensorEffects, DepthTimeOffsetRendersDepthAtTheShiftedTime) {
  SequenceOptions o = quick("walking_xyz");
  o.sensor.depth.enabled = false;
  o.sensor.color.enabled = false;
  SequenceOptions offset = o;
  offset.sensor.depth_time_offset_s = 0.012;
  const SequenceGenerator gen(o), gen_off(offset);
  const int k = 5;
  const SyntheticFrame f = gen_off.render(k), base = gen.render(k);
  EXPECT_DOUBLE_EQ(f.depth_timestamp, f.timestamp + 0.012);
  EXPECT_TRUE(f.T_wc.isApprox(gen.poseWc(k), 0));
  // Depth: exactly the global render at t + offset (camera and movers then), quantised to 1 / 5000 m.
  const RenderedImage shifted = gen.renderExactAt(gen.time(k) + 0.012, true, true, false);
  EXPECT_EQ(maxDifference(f.exact_depth, shifted.depth), 0);
  cv::Mat expected(shifted.depth.size(), CV_16U, cv::Scalar(0));
  for (int y = 0; y < expected.rows; ++y)
    for (int x = 0; x < expected.cols; ++x) {
      const double z = shifted.depth.at<float>(y, x);  // in range (0.4, 5] m: a reading
      if (z > 0.4 && z <= 5.0) expected.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(std::lround(z * 5000.0));
    }
  EXPECT_EQ(maxDifference(f.depth_raw, expected), 0);
  EXPECT_GT(cv::norm(f.depth_raw, base.depth_raw, cv::NORM_L1), 0);  // the camera moved in 12 ms
  // Colour and masks stay at the colour time stamp.
  EXPECT_EQ(maxDifference(f.bgr, base.bgr), 0);
  EXPECT_EQ(maxDifference(f.mask, base.mask), 0);
}

TEST(SensorEffects, DepthTimeOffsetIsInTheWrittenStamps) {
  SequenceOptions o = quick("static_xyz", 3);
  o.sensor.depth_time_offset_s = -0.01;
  const std::filesystem::path dir = testing::scratchDir("amos_depth_offset") / "sequence";
  renderSequence(o, dir.string());
  std::ifstream assoc(dir / "associations.txt");
  std::string line;
  int rows = 0;
  while (std::getline(assoc, line)) {
    std::istringstream in(line);
    double t_rgb = 0, t_depth = 0;
    std::string rgb, depth;
    in >> t_rgb >> rgb >> t_depth >> depth;
    EXPECT_NEAR(t_depth - t_rgb, -0.01, 2e-6) << line;
    EXPECT_EQ(depth, "depth/" + formatTimestamp(t_depth) + ".png") << line;
    EXPECT_TRUE(std::filesystem::exists(dir / depth)) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 3);
  std::ifstream depth_list(dir / "depth.txt");
  std::string all((std::istreambuf_iterator<char>(depth_list)), std::istreambuf_iterator<char>());
  EXPECT_NE(all.find(formatTimestamp(o.start_timestamp - 0.01) + " depth/"), std::string::npos) << all;
  std::ifstream info(dir / "instances.json");
  std::string json((std::istreambuf_iterator<char>(info)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"depth_time_offset_s\": -0.01"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(SensorEffects, DepthNoiseAndColourNoiseSwitchApart) {
  SequenceOptions noisy_depth = quick("static_xyz"), noisy_colour = noisy_depth;
  noisy_depth.sensor.color.enabled = false;
  noisy_colour.sensor.depth.enabled = false;
  const SequenceGenerator a(noisy_depth), b(noisy_colour);
  const int k = 4;
  const RenderedImage exact = a.renderExact(k, true, true, true);
  const SyntheticFrame fa = a.render(k), fb = b.render(k);
  // Exact colour, noisy depth: the colour is the exact render in 8 bits; the depth scatters as sigma(z).
  EXPECT_EQ(maxDifference(fa.bgr, eightBit(exact.color)), 0);
  double sum2 = 0;
  long n = 0;
  for (int y = 0; y < fa.depth.rows; ++y)
    for (int x = 0; x < fa.depth.cols; ++x) {
      const double z = exact.depth.at<float>(y, x), m = fa.depth.at<float>(y, x);
      if (m <= 0 || !(z > 0.4) || z > 5) continue;
      const double e = (m - z) / std::hypot(depthSigma(noisy_depth.sensor.depth, z), 0.0002 / std::sqrt(12.0));
      sum2 += e * e;
      ++n;
    }
  ASSERT_GT(n, 200000);
  EXPECT_NEAR(std::sqrt(sum2 / n), 1.0, 0.03);
  // Exact depth, noisy colour: depth is the exact render quantised; the colour is not the exact render.
  for (int y = 0; y < fb.depth.rows; y += 3)
    for (int x = 0; x < fb.depth.cols; x += 3) {
      const double z = exact.depth.at<float>(y, x);
      const int expected = z > 0.4 && z <= 5.0 ? static_cast<int>(std::lround(z * 5000.0)) : 0;
      ASSERT_EQ(fb.depth_raw.at<std::uint16_t>(y, x), expected) << x << " " << y;
    }
  EXPECT_GT(cv::norm(fb.bgr, eightBit(exact.color), cv::NORM_L1) / fb.bgr.total(), 1.0);
}

TEST(SensorEffects, DisparityQuantisationGivesKinectDepthSteps) {
  SensorOptions o;
  o.depth.enabled = false;
  o.disparity.enabled = true;
  const SensorModel sensor(o);
  const int W = 2000;
  cv::Mat exact(1, W, CV_32F), incidence(1, W, CV_32F, cv::Scalar(1));
  for (int x = 0; x < W; ++x) exact.at<float>(0, x) = static_cast<float>(1.0 + 3.0 * x / W);  // 1 .. 4 m
  Random rng(1);
  const cv::Mat d = sensor.measureDepth(exact, incidence, rng);
  std::vector<double> levels;
  for (int x = 0; x < W; ++x) {
    const double z = exact.at<float>(0, x), m = d.at<std::uint16_t>(0, x) / 5000.0;
    const double step = 2.87e-3 * z * z;
    ASSERT_LE(std::abs(m - z), 0.5 * step * 1.05 + 1e-4) << z;
    if (levels.empty() || m != levels.back()) levels.push_back(m);
  }
  // Near 2 m and 4 m the steps are about 2.87e-3 z^2: 11.5 mm and 46 mm.
  for (double z : {2.0, 3.9}) {
    const auto above = std::upper_bound(levels.begin(), levels.end(), z);
    ASSERT_TRUE(above != levels.begin() && above != levels.end());
    EXPECT_NEAR(*above - *(above - 1), 2.87e-3 * z * z, 0.1 * 2.87e-3 * z * z) << z;
  }
}

TEST(SensorEffects, OptionsRefuseTimingsOutsideAFrame) {
  SensorOptions o;
  o.depth_time_offset_s = 0.015;
  EXPECT_NO_THROW(o.check());
  o.depth_time_offset_s = -0.02;  // beyond half a frame at 30 Hz: the nearest depth stamp would be another frame's
  EXPECT_THROW(o.check(), core::Error);
  o.depth_time_offset_s = 0;
  o.rolling_shutter_s = 0.04;
  EXPECT_THROW(o.check(), core::Error);
  o.rolling_shutter_s = 0.03;
  o.rolling_shutter_band_rows = 0;
  EXPECT_THROW(o.check(), core::Error);
  o.rolling_shutter_band_rows = 8;
  EXPECT_NO_THROW(o.check());
  o.disparity.baseline_m = 0;
  EXPECT_THROW(o.check(), core::Error);
}

}  // namespace
}  // namespace amos::synth
