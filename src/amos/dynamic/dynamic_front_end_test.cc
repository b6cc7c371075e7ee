#include "amos/dynamic/dynamic_front_end.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "amos/core/error.h"
#include "amos/dynamic/test_scenes.h"
#include "amos/evidence/evidence_sources.h"
#include "amos/testing/shared_data.h"
#include "amos/testing/synthetic_scene.h"
#include "amos/testing/test_camera.h"

namespace amos::dynamic {
namespace {

// The front end with the evidence sources its options turn on, as the pipeline builds it.
DynamicFrontEnd frontEnd(const core::PinholeCamera& camera, const DynamicOptions& options) {
  return DynamicFrontEnd(camera, options, evidence::makeEvidenceSources(camera, options));
}

// The scene of testing::crateScene: a wall at Z = 3 m, a floor at Y = 0.7 m, a static crate face at Z = 2 m, a
// static pillar at Z = 1 m and a moving box face at Z = 1.5 m (X in [-0.4, 0], Y in [-0.2, 0.3], plus box_offset),
// all textured, seen by a camera at T_cw. The static part spans three planes: with a single static plane any
// fundamental matrix through its homography would also fit the box, and the epipolar test could not work.
struct Rendered {
  cv::Mat gray, bgr, depth, box_mask;
};

Rendered render(const core::SE3& T_cw, const Eigen::Vector3d& box_offset) {
  static const testing::SyntheticScene scene = testing::crateScene(testing::testIntrinsics());
  const testing::SyntheticView view = scene.render(T_cw, {testing::translation(box_offset)});
  return {view.gray, view.bgr, view.depth, view.mover_mask};
}

struct SyntheticPair {
  Rendered last, current;
  core::SE3 T_cw_last, T_cw_current;
};

// The camera slides 2 cm right and pans 0.3 deg; the box rises 5 cm (across the horizontal epipolar lines).
const SyntheticPair& syntheticPair() {
  static const SyntheticPair pair = [] {
    SyntheticPair p;
    p.T_cw_last = core::SE3::Identity();
    core::Vector6d xi;
    xi << -0.02, 0.0, 0.0, 0.0, 0.3 * M_PI / 180, 0.0;
    p.T_cw_current = core::expSE3(xi) * p.T_cw_last;
    p.last = render(p.T_cw_last, Eigen::Vector3d::Zero());
    p.current = render(p.T_cw_current, Eigen::Vector3d(0.0, -0.05, 0.0));
    return p;
  }();
  return pair;
}

FrontEndInput inputFor(const SyntheticPair& p) {
  FrontEndInput in;
  in.gray = p.current.gray, in.bgr = p.current.bgr, in.depth = p.current.depth;
  in.last_gray = p.last.gray, in.last_depth = p.last.depth;
  in.T_cw_last = p.T_cw_last;
  in.T_cw_initial = p.T_cw_current;
  return in;
}

double coverage(const cv::Mat& mask, const cv::Mat& region) {
  cv::Mat both;
  cv::bitwise_and(mask, region, both);
  return static_cast<double>(cv::countNonZero(both)) / std::max(1, cv::countNonZero(region));
}

TEST(DynamicFrontEnd, GeometryModeMasksTheMovingBoxAndNotTheWall) {
  const SyntheticPair& pair = syntheticPair();
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  const DynamicFrontEnd front_end = frontEnd(testCamera(), options);
  const FrontEndResult out = front_end.process(inputFor(pair));
  const DynamicDiagnostics& d = out.diagnostics;
  ASSERT_TRUE(d.geometry_ran);
  EXPECT_TRUE(d.fundamental_ok);
  EXPECT_GT(d.tracks, 300);
  EXPECT_GT(d.tracks_with_depth, 200);
  EXPECT_GE(d.candidate_clusters, 1);
  EXPECT_GE(d.dynamic_clusters, 1);
  EXPECT_LE(d.dynamic_clusters, d.candidate_clusters);
  EXPECT_GT(d.dynamic_points, 10);
  EXPECT_EQ(out.mask.type(), CV_8U);
  cv::Mat wall;
  cv::bitwise_not(pair.current.box_mask, wall);
  const double box_covered = coverage(out.mask, pair.current.box_mask);
  const double wall_covered = coverage(out.mask, wall);
  EXPECT_GT(box_covered, 0.85) << "wall covered " << wall_covered;
  EXPECT_LT(wall_covered, 0.05) << "box covered " << box_covered;
  // Timings name every stage, in order.
  ASSERT_EQ(out.timings_ms.size(), 7u);
  EXPECT_EQ(out.timings_ms.front().first, "superpixels");
  EXPECT_EQ(out.timings_ms.back().first, "total");
}

// Dynamic.Boundary.borderBlocks (issue 16): the box lowered until only a strip of it, along the image's bottom edge,
// is in view (rows 446-479), rising 5 cm as above. Under the paper's rule that strip lies in the border blocks and
// takes no part in the decisions; under the per-track rule only the tracks within half an LK window of the edge
// abstain, and the strip is found.
TEST(DynamicFrontEnd, PerTrackBorderRuleFindsAMoverAlongTheImageEdge) {
  SyntheticPair pair = syntheticPair();
  pair.last = render(pair.T_cw_last, Eigen::Vector3d(0.0, 0.80, 0.0));
  pair.current = render(pair.T_cw_current, Eigen::Vector3d(0.0, 0.75, 0.0));
  const cv::Rect rows = cv::boundingRect(pair.current.box_mask);
  ASSERT_EQ(rows.y + rows.height, 480);
  ASSERT_LT(rows.height, 40) << "most of the strip must lie in blocks touching the edge";
  cv::Mat wall;
  cv::bitwise_not(pair.current.box_mask, wall);
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  const cv::Mat blocks = frontEnd(testCamera(), options).process(inputFor(pair)).mask;
  options.boundary.border_blocks = false;
  const cv::Mat per_track = frontEnd(testCamera(), options).process(inputFor(pair)).mask;
  EXPECT_GT(coverage(per_track, pair.current.box_mask), 0.7);
  EXPECT_LT(coverage(blocks, pair.current.box_mask), 0.3);
  EXPECT_LT(coverage(per_track, wall), 0.02);
}

TEST(DynamicFrontEnd, PrecomputedPartitionGivesTheSameMask) {
  const SyntheticPair& pair = syntheticPair();
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  const DynamicFrontEnd front_end = frontEnd(testCamera(), options);
  FrontEndInput in = inputFor(pair);
  const FrontEndResult computed_here = front_end.process(in);
  const GeometricPartition ahead =
      computeGeometricPartition(pair.current.bgr, pair.current.depth, options.superpixel, options.cluster);
  in.partition = &ahead;
  const FrontEndResult precomputed = front_end.process(in);
  ASSERT_GT(cv::countNonZero(computed_here.mask), 0);
  EXPECT_EQ(cv::countNonZero(computed_here.mask != precomputed.mask), 0);
  EXPECT_EQ(cv::countNonZero(computed_here.cluster_map != precomputed.cluster_map), 0);
}

TEST(DynamicFrontEnd, StaticSceneGivesAnEmptyMask) {
  const SyntheticPair& pair = syntheticPair();
  // The same camera motion without the box moving.
  const core::PinholeCamera cam = testCamera();
  SyntheticPair still = pair;
  still.current = render(pair.T_cw_current, Eigen::Vector3d::Zero());
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  const FrontEndResult out = frontEnd(cam, options).process(inputFor(still));
  EXPECT_EQ(out.diagnostics.candidate_clusters, 0);
  EXPECT_EQ(out.diagnostics.dynamic_clusters, 0);
  EXPECT_EQ(cv::countNonZero(out.mask), 0);
}

TEST(DynamicFrontEnd, ModesCombinePriorAndGeometry) {
  const SyntheticPair& pair = syntheticPair();
  const core::PinholeCamera cam = testCamera();
  FrontEndInput in = inputFor(pair);
  in.prior_mask = cv::Mat(480, 640, CV_8U, cv::Scalar(0));
  in.prior_mask(cv::Rect(500, 50, 100, 200)).setTo(255);  // a "person" on the static wall
  DynamicOptions options;

  options.mode = DynamicMode::kNone;
  EXPECT_EQ(cv::countNonZero(frontEnd(cam, options).process(in).mask), 0);

  options.mode = DynamicMode::kPrior;
  FrontEndResult prior = frontEnd(cam, options).process(in);
  EXPECT_FALSE(prior.diagnostics.geometry_ran);
  EXPECT_EQ(cv::countNonZero(prior.mask != in.prior_mask), 0);
  EXPECT_EQ(prior.diagnostics.prior_regions, 1);

  options.mode = DynamicMode::kFull;
  FrontEndResult full = frontEnd(cam, options).process(in);
  EXPECT_EQ(coverage(full.mask, in.prior_mask), 1.0);
  EXPECT_GT(coverage(full.mask, pair.current.box_mask), 0.85);

  // The first frame (no last frame) can only use the prior.
  FrontEndInput first = in;
  first.last_gray.release();
  first.last_depth.release();
  FrontEndResult only_prior = frontEnd(cam, options).process(first);
  EXPECT_FALSE(only_prior.diagnostics.geometry_ran);
  EXPECT_EQ(cv::countNonZero(only_prior.mask != in.prior_mask), 0);
}

TEST(DynamicFrontEnd, UsesPrecomputedTracksAndRejectsBadInput) {
  const SyntheticPair& pair = syntheticPair();
  const core::PinholeCamera cam = testCamera();
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  const DynamicFrontEnd front_end = frontEnd(cam, options);
  FrontEndInput in = inputFor(pair);
  const std::vector<PointTrack> tracks = trackCorners(in.last_gray, in.gray, options.tracking);
  in.tracks = &tracks;
  const FrontEndResult a = front_end.process(in);
  in.tracks = nullptr;
  const FrontEndResult b = front_end.process(in);
  EXPECT_EQ(a.diagnostics.tracks, static_cast<int>(tracks.size()));
  EXPECT_EQ(cv::countNonZero(a.mask != b.mask), 0);  // same tracks, same answer: deterministic
  in.depth = cv::Mat(480, 640, CV_16U);
  EXPECT_THROW(front_end.process(in), core::Error);
  EXPECT_THROW(parseDynamicMode("sometimes"), core::Error);
  EXPECT_EQ(parseDynamicMode(toString(DynamicMode::kGeometry)), DynamicMode::kGeometry);
}

// Two consecutive real frames of Bonn crowd (three people walking, moving camera): the pipeline runs end to end
// on real data with the initial pose from the last-frame model, and its output is consistent.
TEST(DynamicFrontEnd, RunsOnRealBonnFrames) {
  AMOS_REQUIRE_DATA("bonn_crowd_dev");
  const std::string dir = testing::dataPath("bonn_crowd_dev/");
  std::ifstream assoc(dir + "associations.txt");
  ASSERT_TRUE(assoc.good()) << "missing " << dir;
  std::vector<std::pair<std::string, std::string>> rows;
  std::string line;
  while (std::getline(assoc, line)) {
    std::istringstream s(line);
    std::string t1, rgb, t2, depth;
    if (s >> t1 >> rgb >> t2 >> depth) rows.emplace_back(rgb, depth);
  }
  ASSERT_GT(rows.size(), 101u);
  auto load = [&](int i, cv::Mat& bgr, cv::Mat& gray, cv::Mat& depth) {
    bgr = cv::imread(dir + rows[i].first, cv::IMREAD_COLOR);
    const cv::Mat raw = cv::imread(dir + rows[i].second, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(bgr.empty());
    ASSERT_EQ(raw.type(), CV_16U);
    raw.convertTo(depth, CV_32F, 1.0 / 5000.0);
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  };
  FrontEndInput in;
  cv::Mat last_bgr;
  load(100, last_bgr, in.last_gray, in.last_depth);
  load(101, in.bgr, in.gray, in.depth);
  const core::PinholeCamera cam(testing::bonnIntrinsics());
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  const std::vector<PointTrack> tracks = trackCorners(in.last_gray, in.gray, options.tracking);
  const auto points_w = backProjectTracks(tracks, in.last_depth, in.T_cw_last, cam, options.reprojection);
  const InitialPoseResult pose = estimateInitialPose({}, lastFrameCorrespondences(tracks, points_w, cam), in.T_cw_last,
                                                     std::nullopt, cam, options.initial_pose);
  ASSERT_TRUE(pose.ok);
  EXPECT_EQ(pose.model, PoseModel::kLastFrame);
  EXPECT_LT(core::translationNorm(pose.T_cw), 0.1);  // 33 ms of hand-held motion
  in.T_cw_initial = pose.T_cw;
  in.tracks = &tracks;
  const FrontEndResult out = frontEnd(cam, options).process(in);
  const DynamicDiagnostics& d = out.diagnostics;
  EXPECT_TRUE(d.fundamental_ok);
  EXPECT_GT(d.tracks, 200);
  EXPECT_GT(d.f_final_inliers, d.tracks / 2);
  EXPECT_GT(d.superpixels, 200);
  EXPECT_EQ(d.clusters, options.cluster.num_clusters);
  EXPECT_LE(d.dynamic_clusters, d.candidate_clusters);
  // The mask is made of whole superpixels, as many as the diagnostics count.
  std::vector<int> in_mask(d.superpixels, 0), size(d.superpixels, 0);
  for (int y = 0; y < out.mask.rows; ++y)
    for (int x = 0; x < out.mask.cols; ++x) {
      const int s = out.superpixel_labels.at<int>(y, x);
      ++size[s];
      in_mask[s] += out.mask.at<uchar>(y, x) != 0;
    }
  int whole = 0;
  for (int s = 0; s < d.superpixels; ++s) {
    EXPECT_TRUE(in_mask[s] == 0 || in_mask[s] == size[s]) << "superpixel " << s << " is cut";
    whole += in_mask[s] == size[s];
  }
  EXPECT_EQ(whole, d.dynamic_superpixels);
  // With the per-superpixel mask switched off the mask is exactly the union of the dynamic clusters.
  options.boundary.superpixel_mask = false;
  const FrontEndResult clusters = frontEnd(cam, options).process(in);
  int expected = 0;
  for (int y = 0; y < clusters.cluster_map.rows; ++y)
    for (int x = 0; x < clusters.cluster_map.cols; ++x)
      expected += clusters.dynamic_cluster[clusters.cluster_map.at<int>(y, x)];
  EXPECT_EQ(cv::countNonZero(clusters.mask), expected);
}

// Why F is fitted outside the potential motion regions: fitted on all tracks of this small-baseline pair, F bends
// to the box's rigid motion (its ~50 tracks outweigh the static parallax), the box satisfies it and is missed.
TEST(DynamicFrontEnd, FittingOnAllTracksLetsARigidMoverHide) {
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  options.reprojection.refit_pose = false;   // the epipolar test alone
  options.epipolar.min_fit_points = 100000;  // never enough tracks outside the candidates: fit on all
  // LK run to 0.01 px: whether the bent F passes the box's tracks is decided by hundredths of a pixel here.
  options.tracking.lk_max_iterations = 30;
  options.tracking.lk_epsilon = 0.01;
  const FrontEndResult all = frontEnd(testCamera(), options).process(inputFor(syntheticPair()));
  EXPECT_EQ(all.diagnostics.f_fit_points, all.diagnostics.tracks);
  EXPECT_LT(coverage(all.mask, syntheticPair().current.box_mask), 0.2);
  options.epipolar.min_fit_points = DynamicOptions{}.epipolar.min_fit_points;
  const FrontEndResult outside = frontEnd(testCamera(), options).process(inputFor(syntheticPair()));
  EXPECT_LT(outside.diagnostics.f_fit_points, outside.diagnostics.tracks);
  EXPECT_GT(coverage(outside.mask, syntheticPair().current.box_mask), 0.85);
}

// The blind spot of the epipolar test: the camera slides sideways (horizontal epipolar lines) and the box moves
// sideways too, along its epipolar lines. F sees nothing; the reprojection error under the pose refitted on the
// static tracks does.
TEST(DynamicFrontEnd, RefittedPoseFindsAMoverSlidingAlongItsEpipolarLines) {
  const core::PinholeCamera cam = testCamera();
  SyntheticPair along = syntheticPair();
  along.current = render(along.T_cw_current, Eigen::Vector3d(0.05, 0.0, 0.0));
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  options.reprojection.refit_pose = false;
  const FrontEndResult epipolar_only = frontEnd(cam, options).process(inputFor(along));
  EXPECT_LT(coverage(epipolar_only.mask, along.current.box_mask), 0.2);
  { const auto& d = epipolar_only.diagnostics; std::cout << "DBG cand " << d.candidate_clusters << " dyn " << d.dynamic_clusters << " dynpts " << d.dynamic_points << " tracks " << d.tracks << " ffit " << d.f_fit_points << " finl " << d.f_final_inliers << " conf " << d.confirmed_clusters << " sp " << d.dynamic_superpixels << "\n"; }
  EXPECT_FALSE(epipolar_only.diagnostics.pose_refit_ok);

  options.reprojection.refit_pose = true;
  const FrontEndResult refitted = frontEnd(cam, options).process(inputFor(along));
  const DynamicDiagnostics& d = refitted.diagnostics;
  EXPECT_TRUE(d.pose_refit_ok);
  EXPECT_GE(d.confirmed_clusters, 1);
  EXPECT_GE(d.pose_refit_inliers, 200);
  // Noise-free rendering: the static tracks' scale is LK's own (a few hundredths to tenths of a pixel).
  EXPECT_LT(d.pose_refit_sigma_px, 0.3);
  EXPECT_DOUBLE_EQ(d.confirm_threshold_px, std::max(1.0, 5.0 * d.pose_refit_sigma_px));
  // The input pose was exact, and the refit keeps it.
  EXPECT_LT(core::translationNorm(refitted.T_cw_judged * along.T_cw_current.inverse()), 1e-3);
  cv::Mat wall;
  cv::bitwise_not(along.current.box_mask, wall);
  EXPECT_GT(coverage(refitted.mask, along.current.box_mask), 0.85);
  EXPECT_LT(coverage(refitted.mask, wall), 0.05);
}

// The per-superpixel mask follows the box's outline, where the union of dynamic clusters (~140 px blobs) also
// covers the wall and floor around it.
TEST(DynamicFrontEnd, SuperpixelMaskFollowsTheMoverOutline) {
  const SyntheticPair& pair = syntheticPair();
  const core::PinholeCamera cam = testCamera();
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  auto precisionOf = [&](const cv::Mat& mask) {
    return coverage(pair.current.box_mask, mask);  // share of the mask on the box
  };
  const FrontEndResult superpixels = frontEnd(cam, options).process(inputFor(pair));
  options.boundary.superpixel_mask = false;
  const FrontEndResult clusters = frontEnd(cam, options).process(inputFor(pair));
  const double sp_precision = precisionOf(superpixels.mask), cl_precision = precisionOf(clusters.mask);
  const double sp_recall = coverage(superpixels.mask, pair.current.box_mask);
  std::cout << "superpixel mask: precision " << sp_precision << " recall " << sp_recall << "; cluster mask: precision "
            << cl_precision << " recall " << coverage(clusters.mask, pair.current.box_mask) << "\n";
  EXPECT_GT(sp_recall, 0.9);
  EXPECT_GT(sp_precision, 0.9);
  EXPECT_GT(sp_precision, cl_precision);
  EXPECT_GT(superpixels.diagnostics.dynamic_superpixels, 0);
}

// Temporal evidence: the tracks that start in the last frame's mask stay out of the pose refit and the F fit, but
// the decisions are still this frame's: the box (in the last mask) is found, a patch of wall in the last mask is
// released.
TEST(DynamicFrontEnd, LastMaskKeepsTracksOutOfTheFitsButDoesNotDecide) {
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  const DynamicFrontEnd front_end = frontEnd(testCamera(), options);
  const FrontEndInput plain = inputFor(syntheticPair());
  const FrontEndResult without = front_end.process(plain);
  ASSERT_TRUE(without.diagnostics.pose_refit_ok);

  FrontEndInput with_box = plain;
  with_box.last_mask = syntheticPair().last.box_mask;
  const FrontEndResult box = front_end.process(with_box);
  ASSERT_TRUE(box.diagnostics.pose_refit_ok);
  EXPECT_LE(box.diagnostics.pose_refit_points, without.diagnostics.pose_refit_points);
  EXPECT_LE(box.diagnostics.f_fit_points, without.diagnostics.f_fit_points);
  EXPECT_GT(coverage(box.mask, syntheticPair().current.box_mask), 0.85);

  // A wall patch away from the box (left half, above the floor) wrongly in the last mask.
  FrontEndInput with_wall = plain;
  with_wall.last_mask = cv::Mat(480, 640, CV_8U, cv::Scalar(0));
  const cv::Rect patch(20, 20, 120, 120);
  with_wall.last_mask(patch).setTo(255);
  int tracks_in_patch = 0;
  for (const PointTrack& t : without.tracks) tracks_in_patch += patch.contains(cv::Point(t.last));
  ASSERT_GT(tracks_in_patch, 10);
  const FrontEndResult wall = front_end.process(with_wall);
  EXPECT_LT(wall.diagnostics.pose_refit_points, without.diagnostics.pose_refit_points);
  EXPECT_GE(wall.diagnostics.pose_refit_points + tracks_in_patch, without.diagnostics.pose_refit_points);
  cv::Mat patch_mask(480, 640, CV_8U, cv::Scalar(0));
  patch_mask(patch).setTo(255);
  EXPECT_LT(coverage(wall.mask, patch_mask), 0.02);
  EXPECT_GT(coverage(wall.mask, syntheticPair().current.box_mask), 0.85);

  // Switched off, the last mask changes nothing.
  options.temporal.exclude_last_mask_from_fits = false;
  const FrontEndResult off = frontEnd(testCamera(), options).process(with_wall);
  EXPECT_EQ(off.diagnostics.pose_refit_points, without.diagnostics.pose_refit_points);
  EXPECT_EQ(cv::countNonZero(off.mask != without.mask), 0);

  // A last mask of the wrong size is an input error.
  FrontEndInput bad = plain;
  bad.last_mask = cv::Mat(10, 10, CV_8U, cv::Scalar(0));
  EXPECT_THROW(front_end.process(bad), core::Error);
}

// Corners on a mover's outline have no single trusted depth; with the smallest error their window's depths allow
// they still count. Here the box's own corners are hidden from Eq. 5 (as if its depth were all edges and holes):
// only its outline tracks, scored by their depth intervals, can make it dynamic.
TEST(DynamicFrontEnd, OutlineTracksScoredByTheirDepthIntervalsFindTheMover) {
  const core::PinholeCamera cam = testCamera();
  SyntheticPair pair = syntheticPair();
  // Holes over the box's inside in the last frame: only its border keeps depth (on the far side, the wall's).
  cv::Mat inside;
  cv::erode(pair.last.box_mask, inside, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(9, 9)));
  pair.last.depth = pair.last.depth.clone();
  pair.last.depth.setTo(0.f, inside);
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  const FrontEndResult with = frontEnd(cam, options).process(inputFor(pair));
  options.reprojection.interval_errors = false;
  const FrontEndResult without = frontEnd(cam, options).process(inputFor(pair));
  EXPECT_GT(coverage(with.mask, pair.current.box_mask), coverage(without.mask, pair.current.box_mask));
  EXPECT_GT(coverage(with.mask, pair.current.box_mask), 0.5);
}

}  // namespace
}  // namespace amos::dynamic

namespace amos::dynamic {
namespace {

// A mover without texture (issue 16's plain chair): the crate scene painted one flat grey, so no corner tracks
// exist, and the box comes 8 cm towards the camera. Only the depth evidence (Dynamic.Depth.enabled) can see it.
TEST(DynamicFrontEnd, DepthEvidenceFindsATexturelessMover) {
  SyntheticPair p = syntheticPair();
  p.current = render(p.T_cw_current, Eigen::Vector3d(0.0, 0.0, -0.08));
  FrontEndInput in = inputFor(p);
  in.gray = cv::Mat(in.gray.size(), CV_8U, cv::Scalar(128));
  in.last_gray = in.gray.clone();
  in.bgr = cv::Mat(in.bgr.size(), CV_8UC3, cv::Scalar(128, 128, 128));
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  const FrontEndResult without = frontEnd(testing::testCamera(), options).process(in);
  EXPECT_EQ(without.diagnostics.tracks, 0);
  EXPECT_EQ(cv::countNonZero(without.mask), 0);
  options.depth.enabled = true;
  const FrontEndResult with = frontEnd(testing::testCamera(), options).process(in);
  const cv::Mat& box = p.current.box_mask;
  const double found = cv::countNonZero(with.mask & box) / static_cast<double>(cv::countNonZero(box));
  const double spill = cv::countNonZero(with.mask & ~box) / static_cast<double>(box.total());
  EXPECT_GT(with.diagnostics.depth_moving_superpixels, 0);
  EXPECT_GT(found, 0.7);
  EXPECT_LT(spill, 0.01);
}

// Dynamic.BaselineTracks (baseline_tracks.h): the box rises 1.5 mm per frame (~0.4 px, inside the one-frame bar of
// max(1 px, 5 sigma)) while the camera slides 2 mm per frame; the frame 10 back sees it 15 mm lower.
TEST(DynamicFrontEnd, BaselineTracksFindAMoverTooSlowForOneFrame) {
  auto pose = [](double x) {
    core::Vector6d xi;
    xi << -x, 0.0, 0.0, 0.0, 0.0, 0.0;
    return core::expSE3(xi);
  };
  const Rendered baseline = render(pose(0.0), Eigen::Vector3d::Zero());
  const Rendered last = render(pose(0.018), Eigen::Vector3d(0.0, -0.0135, 0.0));
  const Rendered current = render(pose(0.020), Eigen::Vector3d(0.0, -0.015, 0.0));
  FrontEndInput in;
  in.gray = current.gray, in.bgr = current.bgr, in.depth = current.depth;
  in.last_gray = last.gray, in.last_depth = last.depth;
  in.T_cw_last = pose(0.018);
  in.T_cw_initial = pose(0.020);
  in.baseline_gray = baseline.gray, in.baseline_depth = baseline.depth;
  in.T_cw_baseline = pose(0.0);
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  const FrontEndResult without = frontEnd(testCamera(), options).process(in);
  options.baseline_tracks.enabled = true;
  const FrontEndResult with = frontEnd(testCamera(), options).process(in);
  cv::Mat wall;
  cv::bitwise_not(current.box_mask, wall);
  EXPECT_LT(coverage(without.mask, current.box_mask), 0.2);
  EXPECT_GT(with.diagnostics.baseline_moving_points, 10);
  // 31 of its points move over the baseline: their superpixels and three clusters; in one frame none does.
  EXPECT_GT(coverage(with.mask, current.box_mask), 0.4);
  EXPECT_LT(coverage(with.mask, wall), 0.02);
}

}  // namespace
}  // namespace amos::dynamic
