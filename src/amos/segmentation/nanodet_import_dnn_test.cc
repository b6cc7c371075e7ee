// Tests of the NanoDet import (block-copy transposes, non-square input) on hand-made blobs and the shared model.
#include "amos/segmentation/nanodet_import_dnn.h"

#include <gtest/gtest.h>

#include <numeric>
#include <opencv2/dnn/all_layers.hpp>
#include <opencv2/imgcodecs.hpp>

#include "amos/core/error.h"
#include "amos/segmentation/nanodet_decoder.h"
#include "amos/testing/shared_data.h"

namespace amos::segmentation {
namespace {

const std::string kDetectorModel = "nanodet_m_320.onnx";
const std::string kDetector = testing::modelPath(kDetectorModel);

cv::Mat countingBlob(const std::vector<int>& shape) {
  cv::Mat blob(static_cast<int>(shape.size()), shape.data(), CV_32F);
  std::iota(blob.ptr<float>(), blob.ptr<float>() + blob.total(), 0.f);
  return blob;
}

// Element of a dense blob at a multi-index.
float at(const cv::Mat& blob, const std::vector<int>& index) {
  std::size_t offset = 0;
  for (int a = 0; a < blob.dims; ++a) offset = offset * static_cast<std::size_t>(blob.size[a]) + index[a];
  return blob.ptr<float>()[offset];
}

// Checks out[i0..in] == in[i_order^-1...] for every element, by brute force over the output indices.
void expectTransposed(const cv::Mat& in, const cv::Mat& out, const std::vector<int>& order) {
  ASSERT_EQ(out.dims, in.dims);
  for (int a = 0; a < in.dims; ++a) ASSERT_EQ(out.size[a], in.size[order[a]]);
  std::vector<int> index(static_cast<std::size_t>(out.dims), 0), source(index.size());
  for (std::size_t k = 0; k < out.total(); ++k) {
    for (std::size_t a = 0; a < index.size(); ++a) source[static_cast<std::size_t>(order[a])] = index[a];
    ASSERT_EQ(at(out, index), at(in, source)) << "element " << k;
    for (int a = out.dims - 1; a >= 0; --a) {
      if (++index[a] < out.size[a]) break;
      index[a] = 0;
    }
  }
}

TEST(NanoDetImport, TransposeMatchesTheDefinition) {
  // NanoDet's channel shuffle: [1, 2, C, h, w] -> (0, 2, 1, 3, 4) keeps the h x w planes whole.
  const cv::Mat shuffle = countingBlob({1, 2, 5, 3, 4});
  expectTransposed(shuffle, transposeBlob(shuffle, {0, 2, 1, 3, 4}), {0, 2, 1, 3, 4});
  // The output heads' [1, C, N] -> (0, 2, 1) moves the innermost axis: element by element.
  const cv::Mat head = countingBlob({1, 6, 7});
  expectTransposed(head, transposeBlob(head, {0, 2, 1}), {0, 2, 1});
  const cv::Mat four = countingBlob({2, 3, 4, 5});
  for (const std::vector<int>& order :
       std::vector<std::vector<int>>{{0, 1, 2, 3}, {3, 2, 1, 0}, {1, 0, 2, 3}, {2, 0, 1, 3}, {0, 3, 1, 2}})
    expectTransposed(four, transposeBlob(four, order), order);
  EXPECT_THROW(transposeBlob(four, {0, 1, 1, 3}), core::Error);
  EXPECT_THROW(transposeBlob(four, {0, 1, 2}), core::Error);
}

TEST(NanoDetImport, ShufflesRunAsBlockCopiesAndOtherImportsAreUntouched) {
  AMOS_REQUIRE_MODELS(kDetectorModel);
  const NanoDetImport square = loadNanoDet(kDetector, 320, {320, 320});
  // 16 ShuffleNetV2 blocks, one shuffle each; the shapes are the export's own.
  EXPECT_EQ(square.block_transposes, 16);
  EXPECT_EQ(square.reshapes_adapted, 0);
  // A plain import after ours gets OpenCV's own layers again (the constructors were unregistered).
  cv::dnn::Net plain = cv::dnn::readNetFromONNX(kDetector);
  int opencv_permutes = 0;
  for (const std::string& name : plain.getLayerNames())
    if (plain.getLayer(plain.getLayerId(name)).dynamicCast<cv::dnn::PermuteLayer>()) ++opencv_permutes;
  EXPECT_EQ(opencv_permutes, 22);  // 16 shuffles + 6 output heads
  // And both give the same outputs.
  cv::Mat input(320, 320, CV_32FC3);
  cv::randu(input, cv::Scalar::all(-2), cv::Scalar::all(2));
  const cv::Mat blob = cv::dnn::blobFromImage(input);
  std::vector<cv::Mat> ours, theirs;
  cv::dnn::Net fast = square.net;
  fast.setInput(blob);
  fast.forward(ours, fast.getUnconnectedOutLayersNames());
  plain.setInput(blob);
  plain.forward(theirs, plain.getUnconnectedOutLayersNames());
  ASSERT_EQ(ours.size(), theirs.size());
  for (std::size_t i = 0; i < ours.size(); ++i) EXPECT_EQ(cv::norm(ours[i], theirs[i], cv::NORM_INF), 0.0) << i;
}

TEST(NanoDetImport, FrameShapedInputFindsThePeopleTheSquareInputFinds) {
  AMOS_REQUIRE_MODELS(kDetectorModel);
  AMOS_REQUIRE_DATA("person_masks");
  const cv::Mat bgr = cv::imread(testing::dataPath("person_masks/rgb/w_xyz_1341846313.553992.png"));
  ASSERT_FALSE(bgr.empty());
  const cv::Size frame_input = detectorInputSize(bgr.size(), 320, /*square=*/false);
  ASSERT_EQ(frame_input, cv::Size(320, 256));
  auto detect = [&](cv::Size input_size) {
    NanoDetImport import = loadNanoDet(kDetector, 320, input_size);
    if (input_size.height != 320) {
      EXPECT_EQ(import.reshapes_adapted, 32);
    }
    const Letterbox lb = makeLetterbox(bgr.size(), input_size);
    cv::Mat input;
    applyLetterbox(bgr, lb).convertTo(input, CV_32FC3);
    cv::subtract(input, cv::Scalar(103.53, 116.28, 123.675), input);
    cv::multiply(input, cv::Scalar(1 / 57.375, 1 / 57.12, 1 / 58.395), input);
    import.net.setInput(cv::dnn::blobFromImage(input));
    std::vector<cv::Mat> outputs;
    import.net.forward(outputs, import.net.getUnconnectedOutLayersNames());
    auto dets = nmsPerClass(decodeNanoDet(nanodetHeadsFromOutputs(outputs, input_size), {0}, 0.35f), 0.5f);
    for (auto& d : dets) d.box = unletterboxBox(d.box, lb, bgr.size());
    std::sort(dets.begin(), dets.end(), [](const Detection& a, const Detection& b) { return a.box.x < b.box.x; });
    return dets;
  };
  const auto square = detect({320, 320});
  const auto frame = detect(frame_input);
  ASSERT_EQ(square.size(), 2u);  // a sitting and a standing person
  ASSERT_EQ(frame.size(), square.size());
  for (std::size_t i = 0; i < frame.size(); ++i) {
    EXPECT_GT(boxIoU(frame[i].box, square[i].box), 0.95) << i;
    EXPECT_NEAR(frame[i].score, square[i].score, 0.05) << i;
  }
}

TEST(NanoDetImport, RejectsInputsThatAreNotMultiplesOf32) {
  AMOS_REQUIRE_MODELS(kDetectorModel);
  EXPECT_THROW(loadNanoDet(kDetector, 320, {320, 240}), core::Error);
}

}  // namespace
}  // namespace amos::segmentation
