// Stage B's person masks: a frame's own segmentation as the network gave it; a segmentation `lag` frames old
// carried over the frames since by their tracks.
#include "amos/system/person_mask_carrier.h"

#include <gtest/gtest.h>

namespace amos::system {
namespace {

// One person: a 40 x 100 block at x0.
segmentation::SegmentationResult personAt(int x0) {
  segmentation::SegmentationResult r;
  segmentation::SegmentedInstance person;
  person.box = cv::Rect(x0, 100, 40, 100);
  person.mask = cv::Mat(person.box.size(), CV_8UC1, cv::Scalar(255));
  r.instances.push_back(person);
  r.mask = cv::Mat(480, 640, CV_8UC1, cv::Scalar(0));
  r.mask(person.box).setTo(255);
  r.dilated_mask = r.mask.clone();
  return r;
}

// Tracks that move everything inside x in [x0, x0 + 40) by dx.
dynamic::FrameFlow flowOf(int x0, float dx) {
  dynamic::FrameFlow flow;
  for (int y = 110; y < 190; y += 20)
    for (int x = x0 + 5; x < x0 + 40; x += 10) flow.tracks.push_back({{float(x), float(y)}, {x + dx, float(y)}});
  return flow;
}

// Segmentation on every third frame, used two frames later; no dilation, so masks compare exactly.
PersonMaskCarrier everyThirdFrameUsedTwoLater() {
  dynamic::PriorScheduleOptions schedule;
  schedule.interval = 3;
  schedule.lag = 2;
  segmentation::MaskDilationOptions no_dilation;
  no_dilation.size = 0;
  return PersonMaskCarrier(no_dilation, schedule);
}

int leftmostColumn(const cv::Mat& mask) {
  for (int x = 0; x < mask.cols; ++x)
    if (cv::countNonZero(mask.col(x)) > 0) return x;
  return -1;
}

TEST(PersonMaskCarrier, OwnSegmentationAsGivenLateOnesCarriedOverTheFramesSince) {
  PersonMaskCarrier carrier = everyThirdFrameUsedTwoLater();
  // The person walks 5 px per frame to the right: at 100 + 5 k in frame k.
  const auto seg0 = personAt(100), seg3 = personAt(115);
  ASSERT_TRUE(carrier.startsFrom(0));
  auto m = carrier.masksFor(0, seg0, {});  // frame 0: its own segmentation
  EXPECT_EQ(cv::norm(m.mask, seg0.mask, cv::NORM_INF), 0);
  EXPECT_FALSE(carrier.startsFrom(0));
  m = carrier.masksFor(1, seg0, flowOf(100, 5));  // frames 1..4 are served by frame 0's segmentation
  EXPECT_EQ(leftmostColumn(m.mask), 105);
  carrier.masksFor(2, seg0, flowOf(105, 5));
  carrier.masksFor(3, seg0, flowOf(110, 5));
  m = carrier.masksFor(4, seg0, flowOf(115, 5));
  EXPECT_EQ(leftmostColumn(m.mask), 120);
  // Frame 5 is the first served by frame 3's segmentation (lag 2): carried over frames 4 and 5.
  ASSERT_TRUE(carrier.startsFrom(3));
  m = carrier.masksFor(5, seg3, flowOf(120, 5));
  EXPECT_EQ(leftmostColumn(m.mask), 125);
}

// A live source: frame 3's segmentation is late at frames 5 and 6, whose masks are carried on from frame 0's; frame
// 7 finds it ready and carries it over frames 4-7. Beyond one period more the carrier refuses (canCarry).
TEST(PersonMaskCarrier, CarriesOnWhileALateSegmentationIsAwaitedThenTakesItOverTheFramesSince) {
  PersonMaskCarrier carrier = everyThirdFrameUsedTwoLater();
  const auto seg0 = personAt(100);
  auto seg3 = personAt(115);
  seg3.instances[0].box.width = 30;  // the network sees the person 30 px wide now: tells the two segmentations apart
  seg3.instances[0].mask = cv::Mat(seg3.instances[0].box.size(), CV_8UC1, cv::Scalar(255));
  carrier.masksFor(0, seg0, {});
  for (int k = 1; k <= 4; ++k) carrier.masksFor(static_cast<FrameNumber>(k), seg0, flowOf(95 + 5 * k, 5));
  ASSERT_TRUE(carrier.startsFrom(3));
  ASSERT_TRUE(carrier.canCarry(5));
  auto m = carrier.carryOn(5, flowOf(120, 5));
  EXPECT_EQ(leftmostColumn(m.mask), 125);
  EXPECT_EQ(cv::countNonZero(m.mask.col(125)), 100);
  m = carrier.carryOn(6, flowOf(125, 5));
  EXPECT_EQ(leftmostColumn(m.mask), 130);
  ASSERT_TRUE(carrier.startsFrom(3));  // still waiting for it
  m = carrier.masksFor(7, seg3, flowOf(130, 5));
  EXPECT_EQ(leftmostColumn(m.mask), 135);                      // frame 3's person, carried over frames 4-7
  EXPECT_EQ(cv::countNonZero(m.mask.row(150)), 30);            // ... with the width frame 3's segmentation gave
  EXPECT_FALSE(carrier.startsFrom(3));
  // Frame 3 + 2 * 3 + 2 - 1 = 10 is the last frame that segmentation may serve.
  EXPECT_TRUE(carrier.canCarry(10));
  EXPECT_FALSE(carrier.canCarry(11));
}

}  // namespace
}  // namespace amos::system
