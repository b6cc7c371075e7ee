#include "amos/dynamic/depth_slic.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "amos/core/stage_timer.h"

#include "amos/core/error.h"
#include "amos/dynamic/boundary_assignment.h"
#include "amos/dynamic/superpixel_metrics.h"

namespace amos::dynamic {
namespace {

// A textured scene whose colour statistics are the same everywhere (random 4x4 grey blocks, fixed seed) and
// whose only structure is geometric: a disc at 1.5 m in front of a wall at 3.0 m. Colour alone cannot find the
// disc; depth can.
struct DepthEdgeScene {
  cv::Mat bgr, depth, reference;  // reference: CV_32S, 1 inside the disc, 0 outside
};

DepthEdgeScene makeDepthEdgeScene() {
  DepthEdgeScene s;
  const int w = 640, h = 480;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> grey(90, 170);
  s.bgr.create(h, w, CV_8UC3);
  for (int by = 0; by < h; by += 4)
    for (int bx = 0; bx < w; bx += 4) {
      const int g = grey(rng);
      s.bgr(cv::Rect(bx, by, 4, 4)).setTo(cv::Scalar(g, g, g));
    }
  s.depth = cv::Mat(h, w, CV_32F, cv::Scalar(3.0f));
  s.reference = cv::Mat(h, w, CV_32S, cv::Scalar(0));
  cv::circle(s.depth, {301, 237}, 113, cv::Scalar(1.5f), cv::FILLED, cv::LINE_8);
  cv::circle(s.reference, {301, 237}, 113, cv::Scalar(1), cv::FILLED, cv::LINE_8);
  return s;
}

cv::Mat referenceEdges(const cv::Mat& reference) { return labelBoundaries(reference); }

// Each test is a process of its own (CTest), so OpenCV's Lab tables are not built yet here: without
// prepareDepthSlic the first superpixels would build them (~0.15 s on one core of the development machine).
TEST(DepthSlic, PreparedBeforeTheFirstFrameItsColourConversionIsImmediate) {
  prepareDepthSlic();
  const DepthEdgeScene scene = makeDepthEdgeScene();
  core::Stopwatch first;
  cv::Mat lab;
  cv::cvtColor(scene.bgr, lab, cv::COLOR_BGR2Lab);
  EXPECT_LT(first.elapsedMs(), 50.0);
}

TEST(DepthSlic, SplitsAlongADepthEdgeThatColourAloneMisses) {
  const DepthEdgeScene scene = makeDepthEdgeScene();
  DepthSlicOptions with_depth;
  DepthSlicOptions colour_only = with_depth;
  colour_only.depth_scale_m = 1e9;  // the depth term vanishes: plain SLIC

  const SuperpixelSegmentation a = computeDepthSlic(scene.bgr, scene.depth, with_depth);
  const SuperpixelSegmentation b = computeDepthSlic(scene.bgr, scene.depth, colour_only);
  const cv::Mat edges = referenceEdges(scene.reference);
  const double recall_depth = boundaryRecall(a.labels, edges, 2);
  const double recall_colour = boundaryRecall(b.labels, edges, 2);
  const double leak_depth = leakage(a.labels, scene.reference);
  const double leak_colour = leakage(b.labels, scene.reference);
  RecordProperty("recall_depth", std::to_string(recall_depth));
  RecordProperty("recall_colour", std::to_string(recall_colour));
  RecordProperty("leak_depth", std::to_string(leak_depth));
  RecordProperty("leak_colour", std::to_string(leak_colour));
  // Colour-only SLIC still has borders everywhere on this texture (so some land near the disc by chance), but it
  // misses a good part of the disc edge and lets superpixels straddle it.
  EXPECT_GT(recall_depth, 0.95);
  EXPECT_LT(recall_colour, 0.85);
  EXPECT_LT(leak_depth, 0.005);
  EXPECT_GT(leak_colour, 3 * leak_depth);
  EXPECT_GT(leak_colour, 0.01);
}

TEST(DepthSlic, SuperpixelsCarryMeanColourPositionAndDepth) {
  const DepthEdgeScene scene = makeDepthEdgeScene();
  const SuperpixelSegmentation seg = computeDepthSlic(scene.bgr, scene.depth, DepthSlicOptions{});
  ASSERT_EQ(seg.labels.size(), scene.bgr.size());
  ASSERT_EQ(seg.labels.type(), CV_32S);
  double min_label, max_label;
  cv::minMaxLoc(seg.labels, &min_label, &max_label);
  EXPECT_EQ(min_label, 0);
  EXPECT_EQ(static_cast<std::size_t>(max_label) + 1, seg.superpixels.size());
  // Near the requested 300: this harsh texture leaves extra fragments above the merge size, real frames fewer.
  EXPECT_GT(seg.superpixels.size(), 200u);
  EXPECT_LT(seg.superpixels.size(), 500u);
  for (const Superpixel& s : seg.superpixels) {
    // The label at the centroid belongs to the disc iff the superpixel's mean depth is the disc's.
    const double r = std::hypot(s.x - 301, s.y - 237);
    if (r < 100) {
      EXPECT_NEAR(s.depth, 1.5, 0.05);
    }
    if (r > 126) {
      EXPECT_NEAR(s.depth, 3.0, 0.05);
    }
    EXPECT_FLOAT_EQ(s.valid_depth_fraction, 1.f);
    EXPECT_NEAR(s.A, 0, 0.1);  // grey: (almost) zero chroma
    EXPECT_GT(s.L, 30);
    EXPECT_LT(s.L, 80);
    EXPECT_EQ(s.cluster, -1);
  }
}

TEST(DepthSlic, InvalidDepthJoinsByColourAndPositionOnly) {
  DepthEdgeScene scene = makeDepthEdgeScene();
  // A band of missing depth across the disc edge (as at real object borders) and a fully invalid corner.
  scene.depth(cv::Rect(380, 200, 60, 80)).setTo(0.f);
  scene.depth(cv::Rect(0, 0, 120, 100)).setTo(std::numeric_limits<float>::quiet_NaN());
  const SuperpixelSegmentation seg = computeDepthSlic(scene.bgr, scene.depth, DepthSlicOptions{});
  int without_depth = 0;
  for (const Superpixel& s : seg.superpixels) {
    EXPECT_TRUE(std::isfinite(s.depth));
    EXPECT_GE(s.valid_depth_fraction, 0.f);
    if (s.valid_depth_fraction == 0.f) {
      EXPECT_EQ(s.depth, 0.f);
      ++without_depth;
    } else {
      EXPECT_GT(s.depth, 1.4f);
      EXPECT_LT(s.depth, 3.1f);
    }
  }
  EXPECT_GT(without_depth, 3);  // the invalid corner holds ~12 superpixels' worth of pixels
  // Where depth is valid, the disc edge is still kept.
  cv::Mat edges = referenceEdges(scene.reference);
  edges(cv::Rect(370, 190, 80, 100)).setTo(0);
  EXPECT_GT(boundaryRecall(seg.labels, edges, 2), 0.9);
}

TEST(DepthSlic, RejectsInvalidOptionsAndInputs) {
  DepthSlicOptions bad;
  bad.scale = 0;
  EXPECT_THROW(bad.check(), core::Error);
  bad = DepthSlicOptions{};
  bad.depth_scale_m = -1;
  EXPECT_THROW(bad.check(), core::Error);
  const cv::Mat bgr(10, 10, CV_8UC3), depth16(10, 10, CV_16U);
  EXPECT_THROW(computeDepthSlic(bgr, depth16, DepthSlicOptions{}), core::Error);
}

TEST(SuperpixelMetrics, RecallAndLeakageOnHandMadeLabels) {
  cv::Mat reference(20, 20, CV_32S, cv::Scalar(0));
  reference(cv::Rect(10, 0, 10, 20)).setTo(1);  // vertical border between x = 9 and x = 10
  cv::Mat shifted(20, 20, CV_32S, cv::Scalar(0));
  shifted(cv::Rect(12, 0, 8, 20)).setTo(1);  // border 2 px to the right
  const cv::Mat edges = labelBoundaries(reference);
  EXPECT_EQ(cv::countNonZero(edges), 20);
  EXPECT_DOUBLE_EQ(boundaryRecall(reference, edges, 0), 1.0);
  EXPECT_DOUBLE_EQ(boundaryRecall(shifted, edges, 1), 0.0);
  EXPECT_DOUBLE_EQ(boundaryRecall(shifted, edges, 2), 1.0);
  EXPECT_DOUBLE_EQ(leakage(reference, reference), 0.0);
  EXPECT_DOUBLE_EQ(leakage(shifted, reference), 40.0 / 400.0);  // columns 10, 11 leak into superpixel 0
  cv::Mat depth(4, 4, CV_32F, cv::Scalar(1.f));
  depth.at<float>(1, 2) = 2.f;
  depth.at<float>(3, 3) = 0.f;                             // invalid: never an edge
  EXPECT_EQ(cv::countNonZero(depthEdges(depth, 0.5)), 3);  // (1,1) right, (0,2) below, (1,2) itself
}

}  // namespace
}  // namespace amos::dynamic

namespace amos::dynamic {
namespace {

// The 8-lane AVX2 assignment loop gives the labels of the 4-lane one bit for bit, on a textured image with depth
// steps and holes at several superpixel counts (different window widths, so different loop tails).
TEST(DepthSlic, Avx2PathGivesTheSameLabels) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "this CPU has no AVX2";
  cv::Mat small(60, 80, CV_8UC3), bgr;
  cv::RNG rng(11);
  rng.fill(small, cv::RNG::UNIFORM, 0, 256);
  cv::resize(small, bgr, cv::Size(640, 480), 0, 0, cv::INTER_LINEAR);
  cv::Mat depth(480, 640, CV_32F);
  for (int y = 0; y < depth.rows; ++y)
    for (int x = 0; x < depth.cols; ++x)
      depth.at<float>(y, x) = (x / 97 + y / 131) % 5 == 0 ? 0.f : 1.0f + 0.37f * ((x / 53 + y / 71) % 4) + 1e-3f * x;
  for (const int count : {150, 300, 611}) {
    DepthSlicOptions options;
    options.num_superpixels = count;
    const SuperpixelSegmentation wide = detail::computeDepthSlic(bgr, depth, options, true);
    const SuperpixelSegmentation narrow = detail::computeDepthSlic(bgr, depth, options, false);
    ASSERT_EQ(wide.superpixels.size(), narrow.superpixels.size()) << count;
    EXPECT_EQ(cv::norm(wide.labels, narrow.labels, cv::NORM_INF), 0) << count << " superpixels";
  }
}

}  // namespace
}  // namespace amos::dynamic

namespace amos::dynamic {
namespace {

// The working-resolution labels give the same superpixel adjacency as the full-resolution ones they are upsampled
// to (superpixelGraph relies on it), at half and at a non-integer scale.
TEST(DepthSlic, WorkingLabelsHaveTheSameNeighbours) {
  cv::Mat small(60, 80, CV_8UC3), bgr;
  cv::RNG rng(5);
  rng.fill(small, cv::RNG::UNIFORM, 0, 256);
  cv::resize(small, bgr, cv::Size(640, 480), 0, 0, cv::INTER_LINEAR);
  const cv::Mat depth(480, 640, CV_32F, cv::Scalar(2.0f));
  for (const double scale : {0.5, 0.37}) {
    DepthSlicOptions options;
    options.scale = scale;
    const SuperpixelSegmentation seg = computeDepthSlic(bgr, depth, options);
    ASSERT_LT(seg.working_labels.cols, seg.labels.cols);
    const int n = static_cast<int>(seg.superpixels.size());
    EXPECT_EQ(superpixelNeighbours(seg.working_labels, n), superpixelNeighbours(seg.labels, n)) << "scale " << scale;
  }
}

}  // namespace
}  // namespace amos::dynamic
