#include "amos/segmentation/segment_masks.h"

#include <fmt/format.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "amos/core/error.h"
#include "amos/segmentation/segmenter_classes.h"

namespace amos::segmentation {

cv::Mat paintInstances(const std::vector<SegmentedInstance>& instances, cv::Size size) {
  cv::Mat frame(size, CV_8UC1, cv::Scalar(0));
  const cv::Rect image(cv::Point(0, 0), size);
  for (const auto& instance : instances) {
    core::require(instance.mask.empty() || (instance.mask.type() == CV_8UC1 && instance.mask.size() == instance.box.size()),
                  "instance mask must be CV_8UC1 of the box size");
    const cv::Rect box = instance.box & image;
    if (box.empty() || instance.mask.empty()) continue;
    const cv::Mat part = instance.mask(cv::Rect(box.tl() - instance.box.tl(), box.size()));
    cv::Mat target = frame(box);
    cv::bitwise_or(target, part, target);
  }
  return frame;
}

cv::Mat dilationKernel(const MaskDilationOptions& options) {
  options.check();
  if (options.size <= 1) return {};
  const int shape = options.shape == "rect" ? cv::MORPH_RECT : options.shape == "cross" ? cv::MORPH_CROSS
                                                                                      : cv::MORPH_ELLIPSE;
  return cv::getStructuringElement(shape, cv::Size(options.size, options.size));
}

namespace {

// Half-width of every kernel row when each row's non-zero elements form one run centred on the anchor column (true
// of OpenCV's ellipse, rect and cross elements); -1 for an empty row. Empty result when some row is not like that.
std::vector<int> centredRowRuns(const cv::Mat& kernel) {
  const int ax = kernel.cols / 2;
  std::vector<int> half_widths;
  for (int i = 0; i < kernel.rows; ++i) {
    const uchar* row = kernel.ptr<uchar>(i);
    int first = -1, last = -1, count = 0;
    for (int j = 0; j < kernel.cols; ++j)
      if (row[j]) {
        if (first < 0) first = j;
        last = j;
        ++count;
      }
    if (count == 0) {
      half_widths.push_back(-1);
      continue;
    }
    if (count != last - first + 1 || ax - first != last - ax) return {};
    half_widths.push_back(ax - first);
  }
  return half_widths;
}

// Grey dilation (pixels beyond the border count as 0) by a kernel given as centred row runs, exactly what
// cv::dilate computes with that kernel, in O(kernel height + largest half-width) passes over the image instead of
// one per kernel element (a 31x31 ellipse has 709): horizontal maxima of growing half-width w come from those of
// w - 1 shifted by one pixel either way, then every kernel row contributes its horizontal maximum shifted by its
// row offset.
cv::Mat dilateByRowRuns(const cv::Mat& src, const std::vector<int>& half_widths) {
  const int r = *std::max_element(half_widths.begin(), half_widths.end());
  const int ay = static_cast<int>(half_widths.size()) / 2;
  cv::Mat padded;
  cv::copyMakeBorder(src, padded, 0, 0, r, r, cv::BORDER_CONSTANT, cv::Scalar(0));
  const int w_padded = padded.cols;
  // horizontal[w](y, x) = max over |d| <= w of padded(y, x + d), valid for x in [w, w_padded - w).
  std::vector<cv::Mat> horizontal(static_cast<std::size_t>(r) + 1);
  horizontal[0] = padded;
  for (int w = 1; w <= r; ++w) {
    const cv::Mat& previous = horizontal[static_cast<std::size_t>(w) - 1];
    cv::Mat& current = horizontal[static_cast<std::size_t>(w)];
    current = cv::Mat::zeros(padded.size(), padded.type());
    cv::Mat middle = current.colRange(1, w_padded - 1);
    cv::max(previous.colRange(0, w_padded - 2), previous.colRange(2, w_padded), middle);
    if (w == 1) cv::max(middle, previous.colRange(1, w_padded - 1), middle);  // |d| <= 1 needs d = 0 as well
  }
  cv::Mat out = cv::Mat::zeros(src.size(), src.type());
  for (int i = 0; i < static_cast<int>(half_widths.size()); ++i) {
    const int w = half_widths[static_cast<std::size_t>(i)];
    if (w < 0) continue;
    const int dy = i - ay;
    const int y0 = std::max(0, -dy), y1 = std::min(src.rows, src.rows - dy);
    if (y0 >= y1) continue;
    cv::Mat target = out.rowRange(y0, y1);
    cv::max(target, horizontal[static_cast<std::size_t>(w)](cv::Rect(r, y0 + dy, src.cols, y1 - y0)), target);
  }
  return out;
}

}  // namespace

cv::Mat dilateMask(const cv::Mat& mask, const MaskDilationOptions& options) {
  core::require(mask.type() == CV_8UC1, "dilateMask expects a CV_8UC1 mask");
  const cv::Mat kernel = dilationKernel(options);
  if (kernel.empty()) return mask.clone();
  cv::Mat out(mask.size(), CV_8UC1, cv::Scalar(0));
  const cv::Rect bounds = cv::boundingRect(mask);
  if (bounds.empty()) return out;
  // Work on the bounding box of the mask grown by the kernel radius: the result is 0 everywhere else.
  const int r = options.size / 2;
  const cv::Rect roi = cv::Rect(bounds.x - r, bounds.y - r, bounds.width + 2 * r, bounds.height + 2 * r) &
                       cv::Rect(0, 0, mask.cols, mask.rows);
  cv::Mat target = out(roi);
  const std::vector<int> runs = centredRowRuns(kernel);
  if (runs.empty()) {
    cv::dilate(mask(roi), target, kernel, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  } else {
    dilateByRowRuns(mask(roi), runs).copyTo(target);
  }
  return out;
}

double maskIoU(const cv::Mat& a, const cv::Mat& b) {
  core::require(a.size() == b.size() && a.type() == CV_8UC1 && b.type() == CV_8UC1,
                "maskIoU expects two CV_8UC1 masks of the same size");
  cv::Mat inter, uni;
  cv::bitwise_and(a != 0, b != 0, inter);
  cv::bitwise_or(a != 0, b != 0, uni);
  const int n_uni = cv::countNonZero(uni);
  return n_uni == 0 ? 1.0 : static_cast<double>(cv::countNonZero(inter)) / n_uni;
}

cv::Mat pasteProbabilityMask(const cv::Mat& probability, const cv::Rect& crop, const cv::Rect& box, float threshold) {
  core::require(probability.type() == CV_32F && !probability.empty(), "probability map must be non-empty CV_32F");
  core::require((box & crop) == box && !box.empty(), "pasteProbabilityMask: crop must contain a non-empty box");
  cv::Mat resized;
  cv::resize(probability, resized, crop.size(), 0, 0, cv::INTER_LINEAR);
  cv::Mat inside = resized(cv::Rect(box.tl() - crop.tl(), box.size()));
  cv::Mat mask;
  cv::compare(inside, threshold, mask, cv::CMP_GT);  // 255 where probability > threshold
  return mask;
}

cv::Rect widenBox(const cv::Rect& box, float widen_x, float widen_y, cv::Size image_size) {
  const int dx = static_cast<int>(std::lround(0.5f * widen_x * box.width));
  const int dy = static_cast<int>(std::lround(0.5f * widen_y * box.height));
  return cv::Rect(box.x - dx, box.y - dy, box.width + 2 * dx, box.height + 2 * dy) &
         cv::Rect(cv::Point(0, 0), image_size);
}

cv::Rect extendBorderCrop(const cv::Rect& box, const cv::Rect& crop, cv::Size image_size, float min_aspect) {
  const int wanted = static_cast<int>(std::lround(min_aspect * crop.height));
  if (min_aspect <= 0.f || crop.width >= wanted) return crop;
  constexpr int kTouch = 2;  // boxes within this many pixels of the border count as cut by it
  const bool left = box.x <= kTouch, right = box.x + box.width >= image_size.width - kTouch;
  if (left == right) return crop;  // not at a side border, or spanning the whole width
  cv::Rect out = crop;
  out.width = wanted;
  if (left) out.x = crop.x + crop.width - wanted;
  return out;
}

cv::Mat imagePatch(const cv::Mat& image, const cv::Rect& rect) {
  const cv::Rect inside = rect & cv::Rect(0, 0, image.cols, image.rows);
  core::require(!inside.empty(), "imagePatch: rectangle entirely outside the image");
  if (inside == rect) return image(rect);
  cv::Mat patch;
  cv::copyMakeBorder(image(inside), patch, inside.y - rect.y, rect.br().y - inside.br().y, inside.x - rect.x,
                     rect.br().x - inside.br().x, cv::BORDER_REFLECT);
  return patch;
}

cv::Mat drawOverlay(const cv::Mat& bgr, const std::vector<SegmentedInstance>& instances) {
  static const cv::Scalar kColours[] = {{0, 0, 255},   {0, 200, 0},   {255, 80, 0},  {0, 200, 255},
                                        {255, 0, 200}, {200, 255, 0}, {128, 0, 255}, {0, 128, 255}};
  cv::Mat overlay = bgr.clone();
  for (std::size_t k = 0; k < instances.size(); ++k) {
    const auto& inst = instances[k];
    const cv::Scalar colour = kColours[k % (sizeof(kColours) / sizeof(kColours[0]))];
    if (!inst.mask.empty()) {
      cv::Mat roi = overlay(inst.box);
      cv::Mat tint(roi.size(), roi.type(), colour);
      cv::Mat blended;
      cv::addWeighted(roi, 0.45, tint, 0.55, 0.0, blended);
      blended.copyTo(roi, inst.mask);
      std::vector<std::vector<cv::Point>> contours;
      cv::findContours(inst.mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE, inst.box.tl());
      cv::drawContours(overlay, contours, -1, colour, 2);
    }
    cv::rectangle(overlay, inst.box, colour, 1);
    const std::string label = fmt::format("{} {:.2f}", cocoClassName(inst.class_id), inst.score);
    const cv::Point at(inst.box.x + 2, std::max(inst.box.y + 14, 14));
    cv::putText(overlay, label, at, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 3);
    cv::putText(overlay, label, at, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255), 1);
  }
  return overlay;
}

cv::Mat contactSheet(const std::vector<cv::Mat>& images, const std::vector<std::string>& captions, int columns,
                     int tile_width) {
  core::require(!images.empty() && columns > 0 && tile_width > 0, "contactSheet: nothing to tile");
  int tile_height = 0;
  for (const auto& image : images) {
    core::require(image.type() == CV_8UC3 && !image.empty(), "contactSheet expects CV_8UC3 images");
    tile_height = std::max(tile_height, (image.rows * tile_width + image.cols / 2) / image.cols);
  }
  const int rows = (static_cast<int>(images.size()) + columns - 1) / columns;
  const int gap = 4;
  cv::Mat sheet(rows * (tile_height + gap) + gap, columns * (tile_width + gap) + gap, CV_8UC3,
                cv::Scalar(40, 40, 40));
  for (std::size_t k = 0; k < images.size(); ++k) {
    const int r = static_cast<int>(k) / columns, c = static_cast<int>(k) % columns;
    const int h = (images[k].rows * tile_width + images[k].cols / 2) / images[k].cols;
    cv::Mat tile = sheet(cv::Rect(gap + c * (tile_width + gap), gap + r * (tile_height + gap), tile_width, h));
    cv::resize(images[k], tile, tile.size(), 0, 0, cv::INTER_AREA);
    if (k < captions.size()) {
      const cv::Point at(4, h - 6);
      cv::putText(tile, captions[k], at, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 3);
      cv::putText(tile, captions[k], at, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1);
    }
  }
  return sheet;
}

}  // namespace amos::segmentation
