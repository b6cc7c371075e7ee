#include "amos/segmentation/segmentation_worker.h"

#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <mutex>

#include "amos/core/error.h"

namespace amos::segmentation {
namespace {

// A segmenter whose single instance is a 4x4 square at x = (blue value of pixel (0, 0)), y = 10; it throws for
// blue value 99, and can be held at a gate to show that submit() does not wait for the segmentation.
class FakeSegmenter : public Segmenter {
 public:
  explicit FakeSegmenter(std::shared_future<void> gate = {}) : gate_(std::move(gate)) {}
  std::vector<SegmentedInstance> segment(const cv::Mat& bgr, const cv::Mat&) override {
    if (gate_.valid()) gate_.wait();
    const int x = bgr.at<cv::Vec3b>(0, 0)[0];
    if (x == 99) throw core::Error("fake failure");
    return {{0, 1.f, cv::Rect(x, 10, 4, 4), cv::Mat(4, 4, CV_8UC1, cv::Scalar(255))}};
  }
  // The earlier instances moved 2 px right, so a test sees which ones it was given; no "detection".
  std::vector<SegmentedInstance> resegment(const cv::Mat&, const cv::Mat&,
                                           const std::vector<SegmentedInstance>& earlier) override {
    std::vector<SegmentedInstance> moved = earlier;
    for (auto& m : moved) m.box.x += 2;
    return moved;
  }
  std::string name() const override { return "fake"; }

 private:
  std::shared_future<void> gate_;
};

cv::Mat frameWithCode(int code) {
  cv::Mat bgr(48, 64, CV_8UC3, cv::Scalar(0, 0, 0));
  bgr.at<cv::Vec3b>(0, 0)[0] = static_cast<uchar>(code);
  return bgr;
}

TEST(SegmentationWorker, SubmitReturnsBeforeTheFrameIsSegmented) {
  std::promise<void> open;
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(open.get_future().share()), {0, "ellipse"});
  auto pending = worker.submit(7, frameWithCode(20));
  // The segmenter is held at the gate, so the result cannot be there yet: the caller is free to extract features.
  EXPECT_EQ(pending.wait_for(std::chrono::milliseconds(0)), std::future_status::timeout);
  open.set_value();
  const SegmentationResult result = pending.get();
  EXPECT_EQ(result.frame_id, 7u);
  ASSERT_EQ(result.instances.size(), 1u);
  EXPECT_EQ(cv::countNonZero(result.mask), 16);
  EXPECT_EQ(result.mask.at<uchar>(10, 20), 255);
}

TEST(SegmentationWorker, ResultsBelongToTheirFramesAndAreDilated) {
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(), {5, "rect"}, 2);
  std::vector<std::future<SegmentationResult>> pending;
  for (int i = 0; i < 6; ++i) pending.push_back(worker.submit(static_cast<std::uint64_t>(i), frameWithCode(5 + 8 * i)));
  for (int i = 0; i < 6; ++i) {
    const SegmentationResult r = pending[static_cast<std::size_t>(i)].get();
    EXPECT_EQ(r.frame_id, static_cast<std::uint64_t>(i));
    EXPECT_EQ(r.mask.at<uchar>(10, 5 + 8 * i), 255);
    EXPECT_EQ(cv::countNonZero(r.mask), 16);
    EXPECT_EQ(cv::countNonZero(r.dilated_mask), 8 * 8);  // 4x4 grown by 2 on each side
    EXPECT_GE(r.latency_ms, r.segment_ms);
  }
}

TEST(SegmentationWorker, SegmenterErrorsReachTheCaller) {
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(), {});
  auto bad = worker.submit(1, frameWithCode(99));
  auto good = worker.submit(2, frameWithCode(3));
  EXPECT_THROW(bad.get(), core::Error);
  EXPECT_EQ(good.get().frame_id, 2u);
}

TEST(SegmentationWorker, ClosingFinishesQueuedFramesAndRefusesNewOnes) {
  std::promise<void> open;
  std::vector<std::future<SegmentationResult>> pending;
  {
    SegmentationWorker worker(std::make_unique<FakeSegmenter>(open.get_future().share()), {}, 4);
    for (int i = 0; i < 3; ++i) pending.push_back(worker.submit(static_cast<std::uint64_t>(i), frameWithCode(i)));
    worker.close();
    EXPECT_THROW(worker.submit(9, frameWithCode(1)), core::Error);
    open.set_value();
  }  // destructor joins after the queued frames
  for (auto& p : pending) EXPECT_EQ(p.wait_for(std::chrono::milliseconds(0)), std::future_status::ready);
  EXPECT_EQ(pending[2].get().frame_id, 2u);
}

TEST(SegmentationWorker, ResubmitMasksTheEarlierResultsObjectsWithoutDetecting) {
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(), {0, "ellipse"});
  auto detected = worker.submit(3, frameWithCode(20)).share();
  // This frame's own "detection" would be at x = 40; the resegmentation follows frame 3's object instead.
  auto carried = worker.resubmit(6, frameWithCode(40), cv::Mat(), detected);
  const SegmentationResult first = detected.get(), second = carried.get();
  EXPECT_TRUE(first.detected);
  EXPECT_FALSE(second.detected);
  EXPECT_EQ(second.frame_id, 6u);
  ASSERT_EQ(second.instances.size(), 1u);
  EXPECT_EQ(second.instances[0].box.x, 22);
  EXPECT_EQ(second.mask.at<uchar>(10, 22), 255);
  EXPECT_EQ(second.mask.at<uchar>(10, 40), 0);
}

TEST(SegmentationWorker, AFailedEarlierSegmentationFailsTheResubmission) {
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(), {});
  auto bad = worker.submit(1, frameWithCode(99)).share();
  auto carried = worker.resubmit(4, frameWithCode(3), cv::Mat(), bad);
  EXPECT_THROW(carried.get(), core::Error);
  EXPECT_THROW(worker.resubmit(5, frameWithCode(3), cv::Mat(), {}), core::Error);
}

TEST(SegmentationWorker, RejectsBadInput) {
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(), {});
  EXPECT_THROW(worker.submit(0, cv::Mat(10, 10, CV_8UC1)), core::Error);
  EXPECT_THROW(SegmentationWorker(nullptr, {}), core::Error);
}

}  // namespace
}  // namespace amos::segmentation
