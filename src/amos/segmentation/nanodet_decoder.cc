#include "amos/segmentation/nanodet_decoder.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"

namespace amos::segmentation {
namespace {

const int kStrides[] = {8, 16, 32};

// Rows x cols view of an output blob [1, N, C] / [N, C] (shares data).
cv::Mat asMatrix(const cv::Mat& blob) {
  core::require(blob.type() == CV_32F, "NanoDet output is not float32");
  const int c = blob.size[blob.dims - 1];
  const int n = static_cast<int>(blob.total() / std::max(c, 1));
  core::require(blob.isContinuous(), "NanoDet output is not continuous");
  return cv::Mat(n, c, CV_32F, const_cast<void*>(static_cast<const void*>(blob.ptr<float>())));
}

}  // namespace

std::vector<NanoDetHead> nanodetHeadsFromOutputs(const std::vector<cv::Mat>& outputs, int input_size, int reg_max) {
  return nanodetHeadsFromOutputs(outputs, cv::Size(input_size, input_size), reg_max);
}

std::vector<NanoDetHead> nanodetHeadsFromOutputs(const std::vector<cv::Mat>& outputs, cv::Size input_size,
                                                 int reg_max) {
  const int box_channels = 4 * (reg_max + 1);
  const std::string input_name = fmt::format("{}x{}", input_size.width, input_size.height);
  std::vector<NanoDetHead> heads;
  for (int stride : kStrides) heads.push_back({stride, input_size.width / stride, cv::Mat(), cv::Mat()});
  for (const cv::Mat& out : outputs) {
    core::require(out.dims >= 2, "NanoDet output with fewer than 2 dimensions");
    cv::Mat m = asMatrix(out);
    bool placed = false;
    for (auto& head : heads) {
      const int cells = (input_size.width / head.stride) * (input_size.height / head.stride);
      if (m.rows != cells) continue;
      cv::Mat& slot = m.cols == box_channels ? head.distributions : head.scores;
      core::require(slot.empty(), fmt::format("two NanoDet outputs of shape [{}, {}]", m.rows, m.cols));
      slot = m;
      placed = true;
    }
    core::require(placed, fmt::format("NanoDet output of shape [{}, {}] fits no stride of a {} input", m.rows, m.cols,
                                      input_name));
  }
  for (const auto& head : heads)
    core::require(!head.scores.empty() && !head.distributions.empty(),
                  fmt::format("NanoDet outputs lack the score or box map of stride {} (input {}): wrong model for "
                              "this input size?",
                              head.stride, input_name));
  return heads;
}

float distributionIntegral(const float* logits, int bins) {
  float max_logit = logits[0];
  for (int k = 1; k < bins; ++k) max_logit = std::max(max_logit, logits[k]);
  float sum = 0.f, weighted = 0.f;
  for (int k = 0; k < bins; ++k) {
    const float e = std::exp(logits[k] - max_logit);
    sum += e;
    weighted += e * static_cast<float>(k);
  }
  return weighted / sum;
}

std::vector<Detection> decodeNanoDet(const std::vector<NanoDetHead>& heads, const std::vector<int>& class_ids,
                                     float score_threshold, int reg_max) {
  const int bins = reg_max + 1;
  std::vector<Detection> detections;
  for (const auto& head : heads) {
    core::require(head.scores.rows == head.distributions.rows && head.distributions.cols == 4 * bins,
                  "NanoDet head with inconsistent score and box maps");
    const int num_classes = head.scores.cols;
    const int cols = head.cols > 0 ? head.cols
                                   : static_cast<int>(std::lround(std::sqrt(static_cast<double>(head.scores.rows))));
    core::require(cols > 0 && head.scores.rows % cols == 0 && (head.cols > 0 || cols * cols == head.scores.rows),
                  "NanoDet head rows do not form a grid");
    for (int r = 0; r < head.scores.rows; ++r) {
      const float* scores = head.scores.ptr<float>(r);
      int best_class = -1;
      float best = score_threshold;
      if (class_ids.empty()) {
        for (int c = 0; c < num_classes; ++c)
          if (scores[c] >= best) best = scores[c], best_class = c;
      } else {
        for (int c : class_ids)
          if (c >= 0 && c < num_classes && scores[c] >= best) best = scores[c], best_class = c;
      }
      if (best_class < 0) continue;
      const float s = static_cast<float>(head.stride);
      const float cx = ((r % cols) + 0.5f) * s - 0.5f, cy = ((r / cols) + 0.5f) * s - 0.5f;
      const float* dist = head.distributions.ptr<float>(r);
      const float left = distributionIntegral(dist, bins) * s, top = distributionIntegral(dist + bins, bins) * s;
      const float right = distributionIntegral(dist + 2 * bins, bins) * s;
      const float bottom = distributionIntegral(dist + 3 * bins, bins) * s;
      detections.push_back({best_class, best, cv::Rect2f(cx - left, cy - top, left + right, top + bottom)});
    }
  }
  return detections;
}

float boxIoU(const cv::Rect2f& a, const cv::Rect2f& b) {
  const float inter = (a & b).area();
  const float uni = a.area() + b.area() - inter;
  return uni > 0.f ? inter / uni : 0.f;
}

std::vector<Detection> nmsPerClass(std::vector<Detection> detections, float iou_threshold) {
  std::stable_sort(detections.begin(), detections.end(),
                   [](const Detection& a, const Detection& b) { return a.score > b.score; });
  std::vector<Detection> kept;
  for (const auto& d : detections) {
    bool suppressed = false;
    for (const auto& k : kept)
      if (k.class_id == d.class_id && boxIoU(k.box, d.box) > iou_threshold) {
        suppressed = true;
        break;
      }
    if (!suppressed) kept.push_back(d);
  }
  return kept;
}

cv::Size detectorInputSize(cv::Size image_size, int side, bool square) {
  core::require(image_size.width > 0 && image_size.height > 0 && side > 0, "detector input for an empty image");
  if (square) return {side, side};
  constexpr int kCoarsestStride = 32;
  const double scale = static_cast<double>(side) / std::max(image_size.width, image_size.height);
  auto fit = [&](int length) {
    const int scaled = static_cast<int>(std::ceil(length * scale - 1e-9));
    return std::min(side, (scaled + kCoarsestStride - 1) / kCoarsestStride * kCoarsestStride);
  };
  return {fit(image_size.width), fit(image_size.height)};
}

Letterbox makeLetterbox(cv::Size image_size, int input_size) {
  return makeLetterbox(image_size, cv::Size(input_size, input_size));
}

Letterbox makeLetterbox(cv::Size image_size, cv::Size input_size) {
  core::require(image_size.width > 0 && image_size.height > 0 && input_size.width > 0 && input_size.height > 0,
                "letterbox of an empty image");
  Letterbox lb;
  lb.input = input_size;
  lb.scale = std::min(static_cast<float>(input_size.width) / image_size.width,
                      static_cast<float>(input_size.height) / image_size.height);
  const int w = static_cast<int>(std::lround(image_size.width * lb.scale));
  const int h = static_cast<int>(std::lround(image_size.height * lb.scale));
  lb.pad_x = static_cast<float>((input_size.width - w) / 2);
  lb.pad_y = static_cast<float>((input_size.height - h) / 2);
  return lb;
}

cv::Mat applyLetterbox(const cv::Mat& bgr, const Letterbox& lb) {
  const int w = static_cast<int>(std::lround(bgr.cols * lb.scale));
  const int h = static_cast<int>(std::lround(bgr.rows * lb.scale));
  cv::Mat input(lb.input, bgr.type(), cv::Scalar::all(0));
  cv::resize(bgr, input(cv::Rect(static_cast<int>(lb.pad_x), static_cast<int>(lb.pad_y), w, h)), cv::Size(w, h), 0,
             0, cv::INTER_LINEAR);
  return input;
}

cv::Rect2f unletterboxBox(const cv::Rect2f& box, const Letterbox& lb, cv::Size image_size) {
  const float x0 = std::clamp((box.x - lb.pad_x) / lb.scale, 0.f, static_cast<float>(image_size.width));
  const float y0 = std::clamp((box.y - lb.pad_y) / lb.scale, 0.f, static_cast<float>(image_size.height));
  const float x1 = std::clamp((box.x + box.width - lb.pad_x) / lb.scale, 0.f, static_cast<float>(image_size.width));
  const float y1 =
      std::clamp((box.y + box.height - lb.pad_y) / lb.scale, 0.f, static_cast<float>(image_size.height));
  return {x0, y0, x1 - x0, y1 - y0};
}

}  // namespace amos::segmentation
