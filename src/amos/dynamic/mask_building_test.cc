#include "amos/dynamic/mask_building.h"

#include <gtest/gtest.h>

#include "amos/dynamic/test_scenes.h"

namespace amos::dynamic {
namespace {

// A 40 x 40 frame of 4 x 4 superpixel blocks of 10 x 10 px, labelled row by row; the left two columns of blocks are
// cluster 0 (dark, L = 20), the right two cluster 1 (bright, L = 80); every superpixel lies at 2 m.
GeometricPartition blockPartition() {
  GeometricPartition partition;
  SuperpixelSegmentation& segmentation = partition.segmentation;
  segmentation.labels.create(40, 40, CV_32S);
  partition.cluster_map.create(40, 40, CV_32S);
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) {
      segmentation.labels.at<int>(y, x) = (y / 10) * 4 + x / 10;
      partition.cluster_map.at<int>(y, x) = x < 20 ? 0 : 1;
    }
  segmentation.superpixels.resize(16);
  for (int s = 0; s < 16; ++s) {
    Superpixel& sp = segmentation.superpixels[s];
    sp.cluster = s % 4 < 2 ? 0 : 1;
    sp.L = sp.cluster == 0 ? 20.f : 80.f;
    sp.depth = 2.f;
    sp.x = 10.f * (s % 4) + 4.5f, sp.y = 10.f * (s / 4) + 4.5f;
  }
  return partition;
}

std::vector<bool> leftHalfSuperpixels() {
  std::vector<bool> left(16);
  for (int s = 0; s < 16; ++s) left[s] = s % 4 < 2;
  return left;
}

PointTrack still(float x, float y) { return {{x, y}, {x, y}}; }

TEST(MaskBuilding, MarksThePixelsOfMarkedLabelsAndKeepsTheRest) {
  const GeometricPartition partition = blockPartition();
  cv::Mat mask(40, 40, CV_8U, cv::Scalar(0));
  mask.at<uchar>(35, 35) = 255;
  std::vector<bool> marked(16, false);
  marked[5] = true;
  markLabelledPixels(partition.segmentation.labels, marked, mask);
  EXPECT_EQ(cv::countNonZero(mask), 101);
  EXPECT_EQ(cv::countNonZero(mask(cv::Rect(10, 10, 10, 10))), 100);
  EXPECT_EQ(mask.at<uchar>(35, 35), 255);
}

TEST(MaskBuilding, WholeClusters) {
  const FrontEndInput in = wallFramePair({40, 40}, 2.f);
  const GeometricPartition partition = blockPartition();
  const DecisionRegions regions = findDecisionRegions(partition.segmentation, partition.cluster_map, 0);
  DynamicOptions options;
  options.boundary.superpixel_mask = false;
  ClusterVoting voting;
  voting.dynamic_cluster = {false, true};
  DynamicDiagnostics diag;
  const std::vector<PointTrack> tracks;
  const CandidateScoring candidates;
  const PoseConfirmation confirmation;
  const EpipolarEvidence epipolar;
  const MaskStages stages{in, tracks, partition, regions, candidates, confirmation, epipolar, voting};
  const DynamicMask mask = buildDynamicMask(stages, {}, options, diag);
  // The right half (border blocks included).
  EXPECT_EQ(cv::countNonZero(mask.mask(cv::Rect(20, 0, 20, 40))), 800);
  EXPECT_EQ(cv::countNonZero(mask.mask(cv::Rect(0, 0, 20, 40))), 0);
  EXPECT_TRUE(mask.dynamic_superpixel.empty());
  EXPECT_EQ(diag.dynamic_superpixels, 0);
}

TEST(MaskBuilding, ADynamicSeedGrowsOverItsClusterAndAStaticOneHoldsTheOther) {
  const GeometricPartition partition = blockPartition();
  const std::vector<bool> border = borderSuperpixels(partition.segmentation.labels, 16, 0);  // all but 5, 6, 9, 10
  const cv::Mat flat(40, 40, CV_32F, cv::Scalar(2.f));
  // Two epipolar violators in superpixel 5 (dynamic cluster 0), two still tracks in superpixel 6 (cluster 1).
  const std::vector<TrackEvidence> evidence = {{{14, 15}, std::nullopt, 10.0},
                                               {{16, 15}, std::nullopt, 10.0},
                                               {{24, 15}, Eigen::Vector2d::Zero(), 0.0},
                                               {{26, 15}, Eigen::Vector2d::Zero(), 0.0}};
  const std::vector<bool> dynamic =
      dynamicSuperpixels({partition.segmentation, flat}, {border, {true, false}}, {evidence, 1.0, false},
                         DynamicOptions{});
  EXPECT_EQ(dynamic, leftHalfSuperpixels());
  // Without a dynamic seed a dynamic cluster is not marked whole.
  EXPECT_EQ(dynamicSuperpixels({partition.segmentation, flat}, {border, {true, false}},
                               {{evidence[2], evidence[3]}, 1.0, false}, DynamicOptions{}),
            std::vector<bool>(16, false));
}

TEST(MaskBuilding, MovingSeedsGrowOverTheUnmeasuredSurfaceAroundThem) {
  // No dynamic cluster; the long-baseline points of superpixel 5 (dark cluster 0) moved: it is a dynamic seed.
  // Superpixel 9 below it, as dark and unmeasured (a door's plain panel), is on its surface (surfaceFromMovingSeeds);
  // superpixel 6 (bright cluster 1) is another surface.
  const GeometricPartition partition = blockPartition();
  const std::vector<bool> border = borderSuperpixels(partition.segmentation.labels, 16, 0);  // all but 5, 6, 9, 10
  const cv::Mat depth(40, 40, CV_32F, cv::Scalar(2.f));
  std::vector<bool> baseline_moving(16, false);
  baseline_moving[5] = true;
  std::vector<int> baseline_points(16, 0);
  baseline_points[5] = 3;
  DynamicOptions options;
  std::vector<bool> only_5(16, false);
  only_5[5] = true;
  EXPECT_EQ(dynamicSuperpixels({partition.segmentation, depth}, {border, {false, false}}, {{}, 1.0, false}, options,
                               {{}, baseline_moving, baseline_points, {}}),
            only_5);
  std::vector<bool> five_and_nine = only_5;
  five_and_nine[9] = true;
  // Not into a superpixel a long-baseline point measured, nor across an occlusion edge, nor into a track-seeded
  // superpixel, nor a step too unlike.
  SuperpixelGraph graph = superpixelGraph(partition.segmentation, depth, options.reprojection.depth_edge_ratio);
  const std::vector<RegionLabel> unseeded(16, RegionLabel::kUnlabelled);
  auto surface = [&](const SuperpixelGraph& g, const std::vector<RegionLabel>& seeds, double max_step) {
    const SurfaceSimilarity similarity{options.superpixel.colour_scale, options.superpixel.depth_scale_m, max_step};
    return surfaceFromMovingSeeds(partition.segmentation.superpixels, g, seeds, border, {baseline_moving, {}},
                                  baseline_points, similarity);
  };
  EXPECT_EQ(surface(graph, unseeded, 1.0), five_and_nine);
  baseline_points[9] = 1;
  EXPECT_EQ(surface(graph, unseeded, 1.0), only_5);
  baseline_points[9] = 0;
  EXPECT_EQ(surface(graph, unseeded, 10.0)[6], true);  // L 20 -> 80: 6 units of colourScale
  std::vector<RegionLabel> static_9 = unseeded;
  static_9[9] = RegionLabel::kStatic;
  EXPECT_EQ(surface(graph, static_9, 1.0), only_5);
  for (std::size_t k = 0; k < graph.neighbours[5].size(); ++k)
    if (graph.neighbours[5][k] == 9) graph.occlusion_edges[5][k] = true;
  EXPECT_EQ(surface(graph, unseeded, 1.0), only_5);
}

TEST(MaskBuilding, ARigidMoversSuperpixelsGrowOverTheirSurfaceWithoutTheBaselineGrowth) {
  // Superpixel 5 follows a rigid mover (rigid_movers.h) and is also a long-baseline seed; superpixel 10's points
  // moved over the long baseline but follow no mover. With Dynamic.RigidMovers.growOverSurface (surface seeds = the
  // rigid movers' superpixels) the label grows from 5 into 9 (same dark surface, unmeasured), not from 10 into 6
  // (bright, unmeasured), and only while 9 is within the mover's region; without it nothing grows.
  const GeometricPartition partition = blockPartition();
  const std::vector<bool> border = borderSuperpixels(partition.segmentation.labels, 16, 0);
  const cv::Mat depth(40, 40, CV_32F, cv::Scalar(2.f));
  std::vector<bool> baseline_moving(16, false), rigid(16, false);
  baseline_moving[5] = baseline_moving[10] = rigid[5] = true;
  std::vector<int> baseline_points(16, 0);
  baseline_points[5] = baseline_points[10] = 3;
  const DynamicOptions options;
  std::vector<bool> seeds_only(16, false);
  seeds_only[5] = seeds_only[10] = true;
  EXPECT_EQ(dynamicSuperpixels({partition.segmentation, depth}, {border, {false, false}}, {{}, 1.0, false}, options,
                               {{}, baseline_moving, baseline_points, {}}),
            seeds_only);
  std::vector<bool> grown = seeds_only;
  grown[9] = true;
  EXPECT_EQ(dynamicSuperpixels({partition.segmentation, depth}, {border, {false, false}}, {{}, 1.0, false}, options,
                               {{}, baseline_moving, baseline_points, {rigid, {}}}),
            grown);
  // Bounded to the mover's region: with 9 outside it the label stays on the seeds; within it, it grows again.
  std::vector<bool> within(16, true);
  within[9] = false;
  EXPECT_EQ(dynamicSuperpixels({partition.segmentation, depth}, {border, {false, false}}, {{}, 1.0, false}, options,
                               {{}, baseline_moving, baseline_points, {rigid, within}}),
            seeds_only);
  within[9] = true;
  EXPECT_EQ(dynamicSuperpixels({partition.segmentation, depth}, {border, {false, false}}, {{}, 1.0, false}, options,
                               {{}, baseline_moving, baseline_points, {rigid, within}}),
            grown);
}

TEST(MaskBuilding, PerSuperpixelMaskFromTheStagesFindings) {
  const FrontEndInput in = wallFramePair({40, 40}, 2.f);
  const GeometricPartition partition = blockPartition();
  const DecisionRegions regions = findDecisionRegions(partition.segmentation, partition.cluster_map, 0);
  const std::vector<PointTrack> tracks = {still(14, 15), still(16, 15), still(24, 15), still(26, 15)};
  CandidateScoring candidates;
  candidates.lifted.points_w.assign(4, std::nullopt);
  PoseConfirmation confirmation;  // no refit: no seeds away from the dynamic clusters
  confirmation.residuals = {std::nullopt, std::nullopt, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  confirmation.static_bar_px = 1.0;
  EpipolarEvidence epipolar;
  epipolar.distance_px = {10.0, 10.0, 0.0, 0.0};
  ClusterVoting voting;
  voting.dynamic_cluster = {true, false};
  DynamicDiagnostics diag;
  const MaskStages stages{in, tracks, partition, regions, candidates, confirmation, epipolar, voting};
  const DynamicMask mask = buildDynamicMask(stages, {}, DynamicOptions{}, diag);
  EXPECT_EQ(mask.dynamic_superpixel, leftHalfSuperpixels());
  EXPECT_EQ(diag.dynamic_superpixels, 8);
  EXPECT_EQ(cv::countNonZero(mask.mask(cv::Rect(0, 0, 20, 40))), 800);
  EXPECT_EQ(cv::countNonZero(mask.mask), 800);
}

TEST(MaskBuilding, TracksOnOcclusionEdgesOrOffTheirSurfaceAbstain) {
  GeometricPartition partition = blockPartition();
  for (int s = 0; s < 16; ++s)
    if (s % 4 >= 2) partition.segmentation.superpixels[s].depth = 3.f;
  partition.segmentation.superpixels[8].depth = 2.5f;  // its tracks (at 2 m) lie off its surface
  cv::Mat depth(40, 40, CV_32F, cv::Scalar(2.f));
  depth(cv::Rect(20, 0, 20, 40)).setTo(3.f);  // a 1 m step between x = 19 and x = 20
  DynamicOptions options;
  options.tracking.lk_window = 5;  // windows of +-2 px
  const std::vector<PointTrack> tracks = {still(10, 15), still(18, 15), still(21, 15), still(5, 25)};
  TrackPoints lifted;
  lifted.points_w = {Eigen::Vector3d(0, 0, 2), std::nullopt, std::nullopt, Eigen::Vector3d(0, 0, 2)};
  // The edge tracks' windows allow any depth from the near side (2 m) on: no point, an interval.
  lifted.intervals = {std::nullopt, DepthInterval{2.0, 3.0}, DepthInterval{2.0, 3.0}, std::nullopt};
  const std::vector<std::optional<Eigen::Vector2d>> residuals(4, Eigen::Vector2d(5, 0));
  const std::vector<double> epipolar = {7.0, 7.0, 7.0, 7.0};
  const std::vector<TrackEvidence> evidence =
      seedingEvidence({tracks, lifted, residuals, epipolar}, depth, depth, partition.segmentation, 1.0, options);
  // Kept: the track on the flat part with its epipolar distance, and the edge track that cannot be static whose
  // superpixel is the near (occluding) side, by its motion only. Abstaining: the edge track whose superpixel is the
  // far side, and the one off its superpixel's surface.
  ASSERT_EQ(evidence.size(), 2u);
  EXPECT_EQ(evidence[0].pixel, cv::Point2f(10, 15));
  EXPECT_EQ(evidence[0].epipolar_px, 7.0);
  EXPECT_EQ(evidence[1].pixel, cv::Point2f(18, 15));
  EXPECT_EQ(evidence[1].epipolar_px, 0.0);
  // A still edge track (residual below the static bar) abstains too.
  const std::vector<std::optional<Eigen::Vector2d>> small(4, Eigen::Vector2d(0.5, 0));
  EXPECT_EQ(seedingEvidence({tracks, lifted, small, epipolar}, depth, depth, partition.segmentation, 1.0, options).size(),
            1u);
}

}  // namespace
}  // namespace amos::dynamic
