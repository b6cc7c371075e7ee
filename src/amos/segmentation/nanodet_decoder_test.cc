#include "amos/segmentation/nanodet_decoder.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "amos/core/error.h"

namespace amos::segmentation {
namespace {

constexpr int kInput = 320;
constexpr int kBins = 8;  // reg_max 7

// Raw outputs of a NanoDet-m at 320 as OpenCV returns them: [1, N, 80] score maps and [1, N, 32] box maps,
// all zero (no object, every side distribution uniform).
struct FakeOutputs {
  std::vector<cv::Mat> scores, boxes;  // index 0, 1, 2 = stride 8, 16, 32
  FakeOutputs() {
    for (int stride : {8, 16, 32}) {
      const int n = (kInput / stride) * (kInput / stride);
      const int score_shape[] = {1, n, 80}, box_shape[] = {1, n, 4 * kBins};
      scores.emplace_back(3, score_shape, CV_32F, cv::Scalar(0));
      boxes.emplace_back(3, box_shape, CV_32F, cv::Scalar(0));
    }
  }
  // Sets class score and a one-hot side distribution (bins in units of the stride) at cell (i, j) of head h.
  void place(int h, int i, int j, int class_id, float score, int left, int top, int right, int bottom) {
    const int stride = 8 << h, cols = kInput / stride, row = i * cols + j;
    scores[h].ptr<float>(0, row)[class_id] = score;
    float* dist = boxes[h].ptr<float>(0, row);
    const int sides[] = {left, top, right, bottom};
    for (int s = 0; s < 4; ++s)
      for (int k = 0; k < kBins; ++k) dist[s * kBins + k] = (k == sides[s]) ? 30.f : 0.f;
  }
  // Outputs in a scrambled order: the decoder must tell them apart by shape.
  std::vector<cv::Mat> outputs() const { return {boxes[2], scores[0], boxes[1], scores[2], boxes[0], scores[1]}; }
};

TEST(NanoDetDecoder, DistributionIntegralIsTheExpectedBin) {
  const float uniform[kBins] = {0, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_NEAR(distributionIntegral(uniform, kBins), 3.5f, 1e-5f);
  float one_hot[kBins] = {0, 0, 0, 0, 0, 0, 0, 0};
  one_hot[5] = 40.f;
  EXPECT_NEAR(distributionIntegral(one_hot, kBins), 5.f, 1e-4f);
  const float two_equal[kBins] = {-50, -50, 10, -50, 10, -50, -50, -50};  // half at 2, half at 4
  EXPECT_NEAR(distributionIntegral(two_equal, kBins), 3.f, 1e-4f);
}

TEST(NanoDetDecoder, DecodesAKnownBoxFromScrambledOutputs) {
  FakeOutputs fake;
  // Stride 16, cell (i=5, j=7): centre (7.5*16-0.5, 5.5*16-0.5) = (119.5, 87.5); sides 2,3,1,4 bins of 16 px.
  fake.place(1, 5, 7, /*person*/ 0, 0.9f, 2, 3, 1, 4);
  const auto heads = nanodetHeadsFromOutputs(fake.outputs(), kInput);
  ASSERT_EQ(heads.size(), 3u);
  EXPECT_EQ(heads[1].stride, 16);
  EXPECT_EQ(heads[1].scores.rows, 400);
  const auto dets = decodeNanoDet(heads, {0}, 0.35f);
  ASSERT_EQ(dets.size(), 1u);
  EXPECT_EQ(dets[0].class_id, 0);
  EXPECT_FLOAT_EQ(dets[0].score, 0.9f);
  EXPECT_NEAR(dets[0].box.x, 119.5f - 32.f, 1e-3f);
  EXPECT_NEAR(dets[0].box.y, 87.5f - 48.f, 1e-3f);
  EXPECT_NEAR(dets[0].box.width, 48.f, 1e-3f);
  EXPECT_NEAR(dets[0].box.height, 112.f, 1e-3f);
}

TEST(NanoDetDecoder, ClassFilterAndThreshold) {
  FakeOutputs fake;
  fake.place(0, 10, 10, 0, 0.8f, 1, 1, 1, 1);   // person
  fake.place(2, 3, 4, 56, 0.95f, 2, 2, 2, 2);   // chair
  fake.place(0, 30, 30, 0, 0.2f, 1, 1, 1, 1);   // weak person, below threshold
  const auto heads = nanodetHeadsFromOutputs(fake.outputs(), kInput);
  const auto people = decodeNanoDet(heads, {0}, 0.35f);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_NEAR(people[0].box.x, 10.5f * 8 - 0.5f - 8.f, 1e-3f);
  const auto all = decodeNanoDet(heads, {}, 0.35f);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_TRUE(std::any_of(all.begin(), all.end(), [](const Detection& d) { return d.class_id == 56; }));
  EXPECT_EQ(decodeNanoDet(heads, {0}, 0.1f).size(), 2u);
}

TEST(NanoDetDecoder, MissingHeadIsAnError) {
  FakeOutputs fake;
  auto outputs = fake.outputs();
  outputs.pop_back();  // drop a score map
  EXPECT_THROW(nanodetHeadsFromOutputs(outputs, kInput), core::Error);
  // The 320 outputs do not fit a 416 input.
  EXPECT_THROW(nanodetHeadsFromOutputs(fake.outputs(), 416), core::Error);
}

TEST(NanoDetDecoder, NmsIsPerClass) {
  std::vector<Detection> dets = {
      {0, 0.6f, {0, 0, 100, 100}},    // suppressed by the 0.9 person (IoU 0.81)
      {0, 0.9f, {5, 5, 100, 100}},
      {56, 0.7f, {5, 5, 100, 100}},   // other class: kept
      {0, 0.5f, {300, 300, 50, 50}},  // far away: kept
  };
  const auto kept = nmsPerClass(dets, 0.5f);
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_FLOAT_EQ(kept[0].score, 0.9f);
  EXPECT_EQ(kept[1].class_id, 56);
  EXPECT_FLOAT_EQ(kept[2].score, 0.5f);
  EXPECT_EQ(nmsPerClass(dets, 0.9f).size(), 4u);
}

TEST(NanoDetDecoder, DecodesANonSquareGrid) {
  // A 320x256 input: stride 16 has a 20 x 16 grid (cols x rows). Cell (i=15, j=19), the bottom-right one.
  const cv::Size input(320, 256);
  std::vector<cv::Mat> outputs;
  for (int stride : {8, 16, 32}) {
    const int n = (input.width / stride) * (input.height / stride);
    const int score_shape[] = {1, n, 80}, box_shape[] = {1, n, 4 * kBins};
    outputs.emplace_back(3, score_shape, CV_32F, cv::Scalar(0));
    outputs.emplace_back(3, box_shape, CV_32F, cv::Scalar(0));
  }
  const int row = 15 * 20 + 19;
  outputs[2].ptr<float>(0, row)[0] = 0.8f;
  float* dist = outputs[3].ptr<float>(0, row);
  for (int s = 0; s < 4; ++s)
    for (int k = 0; k < kBins; ++k) dist[s * kBins + k] = k == 1 ? 30.f : 0.f;
  const auto heads = nanodetHeadsFromOutputs(outputs, input);
  EXPECT_EQ(heads[1].cols, 20);
  const auto dets = decodeNanoDet(heads, {0}, 0.35f);
  ASSERT_EQ(dets.size(), 1u);
  EXPECT_NEAR(dets[0].box.x, 19.5f * 16 - 0.5f - 16.f, 1e-3f);
  EXPECT_NEAR(dets[0].box.y, 15.5f * 16 - 0.5f - 16.f, 1e-3f);
  // The same outputs do not fit a square input.
  EXPECT_THROW(nanodetHeadsFromOutputs(outputs, 320), core::Error);
}

TEST(NanoDetDecoder, DetectorInputKeepsTheFrameShape) {
  EXPECT_EQ(detectorInputSize({640, 480}, 320, true), cv::Size(320, 320));
  EXPECT_EQ(detectorInputSize({640, 480}, 320, false), cv::Size(320, 256));
  EXPECT_EQ(detectorInputSize({640, 480}, 416, false), cv::Size(416, 320));
  EXPECT_EQ(detectorInputSize({480, 640}, 320, false), cv::Size(256, 320));
  EXPECT_EQ(detectorInputSize({1280, 720}, 320, false), cv::Size(320, 192));
  EXPECT_EQ(detectorInputSize({500, 500}, 320, false), cv::Size(320, 320));
  // 320x256 letterbox: the 320x240 frame image centred, 8 rows of padding above and below.
  const Letterbox lb = makeLetterbox({640, 480}, cv::Size(320, 256));
  EXPECT_FLOAT_EQ(lb.scale, 0.5f);
  EXPECT_FLOAT_EQ(lb.pad_x, 0.f);
  EXPECT_FLOAT_EQ(lb.pad_y, 8.f);
  EXPECT_EQ(applyLetterbox(cv::Mat(480, 640, CV_8UC3, cv::Scalar::all(1)), lb).size(), cv::Size(320, 256));
}

TEST(NanoDetDecoder, BoxIoU) {
  EXPECT_FLOAT_EQ(boxIoU({0, 0, 10, 10}, {5, 0, 10, 10}), 50.f / 150.f);
  EXPECT_FLOAT_EQ(boxIoU({0, 0, 10, 10}, {20, 20, 5, 5}), 0.f);
}

TEST(NanoDetDecoder, LetterboxMapsBackToTheImage) {
  const Letterbox lb = makeLetterbox({640, 480}, 320);
  EXPECT_FLOAT_EQ(lb.scale, 0.5f);
  EXPECT_FLOAT_EQ(lb.pad_x, 0.f);
  EXPECT_FLOAT_EQ(lb.pad_y, 40.f);
  const cv::Rect2f box = unletterboxBox({10, 50, 100, 60}, lb, {640, 480});
  EXPECT_FLOAT_EQ(box.x, 20.f);
  EXPECT_FLOAT_EQ(box.y, 20.f);
  EXPECT_FLOAT_EQ(box.width, 200.f);
  EXPECT_FLOAT_EQ(box.height, 120.f);
  // Boxes reaching into the padding are clipped to the image.
  const cv::Rect2f clipped = unletterboxBox({-5, 20, 30, 40}, lb, {640, 480});
  EXPECT_FLOAT_EQ(clipped.x, 0.f);
  EXPECT_FLOAT_EQ(clipped.y, 0.f);
  EXPECT_FLOAT_EQ(clipped.height, 40.f);  // (20 + 40 - 40) / 0.5

  cv::Mat image(480, 640, CV_8UC3, cv::Scalar(10, 20, 30));
  const cv::Mat input = applyLetterbox(image, lb);
  ASSERT_EQ(input.size(), cv::Size(320, 320));
  EXPECT_EQ(input.at<cv::Vec3b>(20, 160), cv::Vec3b(0, 0, 0));      // padding above
  EXPECT_EQ(input.at<cv::Vec3b>(160, 160), cv::Vec3b(10, 20, 30));  // image
  EXPECT_EQ(input.at<cv::Vec3b>(300, 160), cv::Vec3b(0, 0, 0));     // padding below
}

}  // namespace
}  // namespace amos::segmentation
