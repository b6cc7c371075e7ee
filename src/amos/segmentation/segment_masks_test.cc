#include "amos/segmentation/segment_masks.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "amos/core/error.h"

namespace amos::segmentation {
namespace {

TEST(SegmentMasks, PaintInstancesUnitesBoxMasks) {
  SegmentedInstance a{0, 0.9f, cv::Rect(10, 10, 4, 3), cv::Mat(3, 4, CV_8UC1, cv::Scalar(255))};
  SegmentedInstance b{0, 0.8f, cv::Rect(12, 11, 5, 5), cv::Mat(5, 5, CV_8UC1, cv::Scalar(0))};
  b.mask(cv::Rect(0, 0, 2, 1)).setTo(255);  // image pixels (12..13, 11): inside a as well
  b.mask.at<uchar>(4, 4) = 255;             // image pixel (16, 15)
  const cv::Mat frame = paintInstances({a, b}, cv::Size(32, 24));
  ASSERT_EQ(frame.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(frame), 12 + 1);
  EXPECT_EQ(frame.at<uchar>(10, 10), 255);
  EXPECT_EQ(frame.at<uchar>(12, 13), 255);
  EXPECT_EQ(frame.at<uchar>(15, 16), 255);
  EXPECT_EQ(frame.at<uchar>(14, 14), 0);

  SegmentedInstance wrong{0, 0.5f, cv::Rect(0, 0, 4, 4), cv::Mat(3, 3, CV_8UC1, cv::Scalar(255))};
  EXPECT_THROW(paintInstances({wrong}, cv::Size(32, 24)), core::Error);
}

TEST(SegmentMasks, PasteProbabilityKeepsOnlyTheBoxPart) {
  // Probability map over a 40x40 crop at (10, 10): left half person (1), right half not (0).
  cv::Mat probability(64, 64, CV_32F, cv::Scalar(0.f));
  probability(cv::Rect(0, 0, 32, 64)).setTo(1.f);
  const cv::Rect crop(10, 10, 40, 40), box(20, 15, 20, 30);
  const cv::Mat mask = pasteProbabilityMask(probability, crop, box, 0.5f);
  ASSERT_EQ(mask.size(), box.size());
  ASSERT_EQ(mask.type(), CV_8UC1);
  // The person/background edge is at crop x = 20, i.e. image x = 30 = box column 10.
  for (int y = 0; y < box.height; ++y) {
    for (int x = 0; x < 9; ++x) EXPECT_EQ(mask.at<uchar>(y, x), 255) << x << "," << y;
    for (int x = 11; x < box.width; ++x) EXPECT_EQ(mask.at<uchar>(y, x), 0) << x << "," << y;
  }
  EXPECT_THROW(pasteProbabilityMask(probability, crop, cv::Rect(5, 5, 10, 10), 0.5f), core::Error);
}

TEST(SegmentMasks, WidenBoxGrowsSymmetricallyAndClips) {
  EXPECT_EQ(widenBox({100, 100, 100, 200}, 0.1f, 0.05f, {640, 480}), cv::Rect(95, 95, 110, 210));
  EXPECT_EQ(widenBox({0, 400, 100, 80}, 0.2f, 0.5f, {640, 480}), cv::Rect(0, 380, 110, 100));
}

TEST(SegmentMasks, DilationUsesTheConfiguredElement) {
  cv::Mat mask(101, 121, CV_8UC1, cv::Scalar(0));
  mask.at<uchar>(50, 60) = 255;
  MaskDilationOptions rect{5, "rect"};
  EXPECT_EQ(cv::countNonZero(dilateMask(mask, rect)), 25);
  MaskDilationOptions ellipse{31, "ellipse"};
  const cv::Mat grown = dilateMask(mask, ellipse);
  EXPECT_EQ(cv::countNonZero(grown), cv::countNonZero(dilationKernel(ellipse)));
  EXPECT_EQ(grown.at<uchar>(50, 60 + 15), 255);
  EXPECT_EQ(grown.at<uchar>(50, 60 + 16), 0);
  EXPECT_EQ(grown.at<uchar>(50 + 15, 60 + 15), 0);  // corner of the square: outside the ellipse
  MaskDilationOptions cross{3, "cross"};
  EXPECT_EQ(cv::countNonZero(dilateMask(mask, cross)), 5);
  MaskDilationOptions off{0, "ellipse"};
  EXPECT_EQ(cv::countNonZero(dilateMask(mask, off)), 1);
  EXPECT_EQ(cv::countNonZero(dilateMask(cv::Mat(40, 40, CV_8UC1, cv::Scalar(0)), ellipse)), 0);
  EXPECT_THROW(dilateMask(mask, MaskDilationOptions{4, "rect"}), core::Error);
}

TEST(SegmentMasks, LocalDilationEqualsFullFrameDilation) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> x(0, 639), y(0, 479), r(1, 40);
  for (int trial = 0; trial < 5; ++trial) {
    cv::Mat mask(480, 640, CV_8UC1, cv::Scalar(0));
    for (int k = 0; k < 3; ++k) cv::circle(mask, {x(rng), y(rng)}, r(rng), cv::Scalar(255), cv::FILLED);
    const MaskDilationOptions options{31, "ellipse"};
    cv::Mat expected;
    cv::dilate(mask, expected, dilationKernel(options), cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
    EXPECT_EQ(cv::countNonZero(dilateMask(mask, options) != expected), 0) << "trial " << trial;
  }
}

// The row-run dilation equals cv::dilate for every structuring element and size, at the image border too.
TEST(SegmentMasks, DilationEqualsOpenCvForEveryShapeAndSize) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> x(-10, 130), y(-10, 90), r(0, 12);
  for (const std::string shape : {"ellipse", "rect", "cross"}) {
    for (int size : {3, 5, 9, 15, 31, 33}) {
      cv::Mat mask(80, 120, CV_8UC1, cv::Scalar(0));
      for (int k = 0; k < 4; ++k) cv::circle(mask, {x(rng), y(rng)}, r(rng), cv::Scalar(255), cv::FILLED);
      mask.at<uchar>(0, 0) = 255;  // corner pixel: the border must count as 0
      const MaskDilationOptions options{size, shape};
      cv::Mat expected;
      cv::dilate(mask, expected, dilationKernel(options), cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
      EXPECT_EQ(cv::countNonZero(dilateMask(mask, options) != expected), 0) << shape << " " << size;
    }
  }
}

TEST(SegmentMasks, MaskIoU) {
  cv::Mat a(10, 10, CV_8UC1, cv::Scalar(0)), b(10, 10, CV_8UC1, cv::Scalar(0));
  EXPECT_DOUBLE_EQ(maskIoU(a, b), 1.0);
  a(cv::Rect(0, 0, 6, 10)).setTo(255);
  b(cv::Rect(3, 0, 6, 10)).setTo(1);
  EXPECT_DOUBLE_EQ(maskIoU(a, b), 30.0 / 90.0);
}

TEST(SegmentMasks, CropsOfPeopleCutByTheBorderAreExtendedBeyondIt) {
  const cv::Size image(640, 480);
  // Cut by the left border: widened to 0.45 * 400 = 180 px, reaching out to the left.
  EXPECT_EQ(extendBorderCrop({0, 40, 60, 400}, {0, 30, 66, 420}, image, 0.45f), cv::Rect(66 - 189, 30, 189, 420));
  // Cut by the right border: extended to the right.
  EXPECT_EQ(extendBorderCrop({590, 40, 50, 400}, {585, 30, 55, 420}, image, 0.45f), cv::Rect(585, 30, 189, 420));
  // Wide enough already, not at a border, or switched off: unchanged.
  EXPECT_EQ(extendBorderCrop({0, 40, 250, 400}, {0, 30, 260, 420}, image, 0.45f), cv::Rect(0, 30, 260, 420));
  EXPECT_EQ(extendBorderCrop({300, 40, 60, 400}, {295, 30, 70, 420}, image, 0.45f), cv::Rect(295, 30, 70, 420));
  EXPECT_EQ(extendBorderCrop({0, 40, 60, 400}, {0, 30, 66, 420}, image, 0.f), cv::Rect(0, 30, 66, 420));
}

TEST(SegmentMasks, ImagePatchMirrorsOutsideTheImage) {
  cv::Mat image(4, 6, CV_8UC1);
  for (int x = 0; x < 6; ++x) image.col(x).setTo(10 * x);
  const cv::Mat inside = imagePatch(image, {1, 0, 3, 4});
  EXPECT_EQ(inside.at<uchar>(0, 0), 10);
  const cv::Mat patch = imagePatch(image, {-2, 0, 5, 4});  // 2 columns left of the image, then columns 0..2
  ASSERT_EQ(patch.size(), cv::Size(5, 4));
  const uchar expected[] = {10, 0, 0, 10, 20};  // BORDER_REFLECT: ...b a | a b c...
  for (int x = 0; x < 5; ++x) EXPECT_EQ(patch.at<uchar>(2, x), expected[x]) << x;
  EXPECT_THROW(imagePatch(image, {10, 0, 2, 2}), core::Error);
}

TEST(SegmentMasks, ContactSheetTilesImages) {
  std::vector<cv::Mat> images(5, cv::Mat(48, 64, CV_8UC3, cv::Scalar(0, 0, 255)));
  const cv::Mat sheet = contactSheet(images, {"a", "b"}, 3, 32);
  EXPECT_EQ(sheet.size(), cv::Size(3 * (32 + 4) + 4, 2 * (24 + 4) + 4));
  EXPECT_EQ(sheet.at<cv::Vec3b>(4 + 2, 4 + 16), cv::Vec3b(0, 0, 255));   // first tile
  EXPECT_EQ(sheet.at<cv::Vec3b>(32 + 2, 40 + 16), cv::Vec3b(0, 0, 255));  // fifth tile (row 1, column 1)
  EXPECT_EQ(sheet.at<cv::Vec3b>(32 + 2, 76 + 16), cv::Vec3b(40, 40, 40));  // no sixth tile
}

}  // namespace
}  // namespace amos::segmentation
