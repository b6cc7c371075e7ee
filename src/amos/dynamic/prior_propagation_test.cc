#include "amos/dynamic/prior_propagation.h"

#include <gtest/gtest.h>

#include "amos/core/error.h"
#include "amos/segmentation/segment_masks.h"

namespace amos::dynamic {
namespace {

using segmentation::dilateMask;
using segmentation::maskIoU;
using segmentation::MaskDilationOptions;
using segmentation::paintInstances;
using segmentation::SegmentedInstance;

const cv::Size kImage(160, 120);

SegmentedInstance block(cv::Rect box) { return {0, 0.9f, box, cv::Mat(box.size(), CV_8UC1, cv::Scalar(255))}; }

// Tracks on a regular grid: those inside `moving` move by `motion`, the others stay.
FrameFlow gridFlow(cv::Rect moving, cv::Point2f motion) {
  FrameFlow flow;
  for (int y = 2; y < kImage.height; y += 6)
    for (int x = 2; x < kImage.width; x += 6) {
      const cv::Point2f p(x + 0.5f, y + 0.5f);
      flow.tracks.push_back({p, moving.contains(cv::Point(x, y)) ? p + motion : p, -1});
    }
  return flow;
}

MaskDilationOptions noDilation() {
  MaskDilationOptions d;
  d.size = 0;
  return d;
}

TEST(PriorSchedule, BaseIsTheNewestScheduledFrameAtLeastLagOld) {
  PriorScheduleOptions o;
  o.interval = 3;
  o.lag = 2;
  const std::size_t expected[] = {0, 0, 0, 0, 0, 3, 3, 3, 6, 6, 6};
  for (std::size_t k = 0; k < std::size(expected); ++k) EXPECT_EQ(o.baseFor(k), expected[k]) << k;
  EXPECT_TRUE(o.isScheduled(6));
  EXPECT_FALSE(o.isScheduled(7));
  o.interval = 1;
  o.lag = 0;  // the paper: every frame its own segmentation
  for (std::size_t k = 0; k < 10; ++k) EXPECT_EQ(o.baseFor(k), k);
}

TEST(PriorSchedule, TheDetectorRunsOnEveryDetectEverythScheduledFrame) {
  PriorScheduleOptions o;
  o.interval = 3;
  o.detect_every = 2;
  for (std::size_t k = 0; k < 19; ++k) EXPECT_EQ(o.detects(k), k % 6 == 0) << k;
  o.detect_every = 1;
  for (std::size_t k = 0; k < 19; ++k) EXPECT_EQ(o.detects(k), o.isScheduled(k)) << k;
  o.detect_every = 0;
  EXPECT_THROW(o.check(), core::Error);
}

TEST(PriorSchedule, RejectsLagBeyondInterval) {
  PriorScheduleOptions o;
  o.interval = 2;
  o.lag = 3;
  EXPECT_THROW(o.check(), core::Error);
  o.lag = 2;
  EXPECT_NO_THROW(o.check());
  o.interval = 0;
  EXPECT_THROW(o.check(), core::Error);
}

TEST(PriorMaskPropagator, FreshSegmentationIsPaintedAsIsAndDilatedLikeTheUnion) {
  MaskDilationOptions dilation;  // 31 px ellipse
  PriorMaskPropagator p(kImage, dilation, {});
  const std::vector<SegmentedInstance> people = {block({20, 30, 20, 40}), block({100, 10, 30, 30})};
  p.reset(people);
  EXPECT_EQ(p.age(), 0);
  EXPECT_DOUBLE_EQ(maskIoU(p.mask(), paintInstances(people, kImage)), 1.0);
  const cv::Mat union_dilated = dilateMask(paintInstances(people, kImage), dilation);
  EXPECT_EQ(cv::countNonZero(p.dilatedMask() != union_dilated), 0);
}

TEST(PriorMaskPropagator, InstanceFollowsTheTracksInsideIt) {
  PriorMaskPropagator p(kImage, noDilation(), {});
  const cv::Rect person(40, 30, 24, 48), other(110, 40, 20, 20);
  p.reset({block(person), block(other)});
  // The person walks 4 px right and 1 px down per frame; the other instance stays; for three frames.
  cv::Rect truth = person;
  for (int i = 0; i < 3; ++i) {
    p.step(gridFlow(truth, {4.f, 1.f}));
    truth += cv::Point(4, 1);
  }
  EXPECT_EQ(p.age(), 3);
  const cv::Mat expected = paintInstances({block(truth), block(other)}, kImage);
  EXPECT_DOUBLE_EQ(maskIoU(p.mask(), expected), 1.0);
}

TEST(PriorMaskPropagator, WithoutTracksAnInstanceKeepsItsLastMotion) {
  PriorScheduleOptions o;
  o.min_tracks = 3;
  PriorMaskPropagator p(kImage, noDilation(), o);
  const cv::Rect person(40, 30, 24, 48);
  p.reset({block(person)});
  p.step(gridFlow(person, {5.f, 0.f}));
  p.step(FrameFlow{});  // tracking lost this frame: no tracks at all
  EXPECT_DOUBLE_EQ(maskIoU(p.mask(), paintInstances({block(person + cv::Point(10, 0))}, kImage)), 1.0);
}

TEST(PriorMaskPropagator, OutliersAtTheOutlineDoNotMoveTheInstance) {
  PriorMaskPropagator p(kImage, noDilation(), {});
  const cv::Rect person(40, 30, 24, 48);
  p.reset({block(person)});
  FrameFlow flow = gridFlow(person, {2.f, 0.f});
  // Two tracks inside the person jump 40 px (slipped onto the background): the median ignores them.
  int changed = 0;
  for (PointTrack& t : flow.tracks)
    if (person.contains(cv::Point(t.last)) && changed < 2) {
      t.current = t.last + cv::Point2f(40.f, 0.f);
      ++changed;
    }
  p.step(flow);
  EXPECT_DOUBLE_EQ(maskIoU(p.mask(), paintInstances({block(person + cv::Point(2, 0))}, kImage)), 1.0);
}

TEST(PriorMaskPropagator, InstanceLeavingTheImageIsClipped) {
  PriorMaskPropagator p(kImage, noDilation(), {});
  const cv::Rect person(140, 30, 20, 40);
  p.reset({block(person)});
  p.step(gridFlow(person, {10.f, 0.f}));
  EXPECT_EQ(cv::countNonZero(p.mask()), 10 * 40);
}

}  // namespace
}  // namespace amos::dynamic
