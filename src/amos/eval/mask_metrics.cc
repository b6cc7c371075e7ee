#include "amos/eval/mask_metrics.h"

#include <cmath>

#include "amos/core/error.h"
#include "amos/eval/stats.h"

namespace amos::eval {

MaskCounts& MaskCounts::operator+=(const MaskCounts& o) {
  true_positive += o.true_positive;
  false_positive += o.false_positive;
  false_negative += o.false_negative;
  true_negative += o.true_negative;
  return *this;
}

MaskCounts compareMasks(const cv::Mat& predicted, const cv::Mat& truth) {
  core::require(predicted.type() == CV_8UC1 && truth.type() == CV_8UC1,
                "compareMasks: both masks must be single-channel 8-bit");
  core::require(predicted.size() == truth.size(), "compareMasks: masks differ in size");
  MaskCounts c;
  for (int y = 0; y < truth.rows; ++y) {
    const uchar* p = predicted.ptr<uchar>(y);
    const uchar* t = truth.ptr<uchar>(y);
    std::int64_t tp = 0, fp = 0, fn = 0;
    for (int x = 0; x < truth.cols; ++x) {
      const bool is_p = p[x] != 0, is_t = t[x] != 0;
      tp += is_p && is_t;
      fp += is_p && !is_t;
      fn += !is_p && is_t;
    }
    c.true_positive += tp;
    c.false_positive += fp;
    c.false_negative += fn;
    c.true_negative += truth.cols - tp - fp - fn;
  }
  return c;
}

namespace {
double ratio(std::int64_t num, std::int64_t den) {
  return den > 0 ? static_cast<double>(num) / static_cast<double>(den) : MaskAccuracy::kNaN;
}

double medianOfDefined(const std::vector<double>& values) {
  std::vector<double> defined;
  for (double v : values)
    if (!std::isnan(v)) defined.push_back(v);
  return computeErrorStats(defined).median;  // NaN when none is defined
}
}  // namespace

double precision(const MaskCounts& c) { return ratio(c.true_positive, c.true_positive + c.false_positive); }
double recall(const MaskCounts& c) { return ratio(c.true_positive, c.true_positive + c.false_negative); }
double iou(const MaskCounts& c) {
  return ratio(c.true_positive, c.true_positive + c.false_positive + c.false_negative);
}

MaskCounts MaskAccuracyAccumulator::add(const cv::Mat& predicted, const cv::Mat& truth) {
  per_frame_.push_back(compareMasks(predicted, truth));
  return per_frame_.back();
}

MaskAccuracy MaskAccuracyAccumulator::summary() const {
  MaskAccuracy a;
  std::vector<double> p, r, j;
  for (const MaskCounts& c : per_frame_) {
    a.total += c;
    ++a.frames;
    if (c.true_positive + c.false_negative > 0) ++a.frames_with_truth;
    p.push_back(precision(c));
    r.push_back(recall(c));
    j.push_back(iou(c));
  }
  a.precision = precision(a.total);
  a.recall = recall(a.total);
  a.iou = iou(a.total);
  const MaskCounts& t = a.total;
  a.dynamic_fraction =
      ratio(t.true_positive + t.false_positive, t.true_positive + t.false_positive + t.false_negative + t.true_negative);
  a.median_precision = medianOfDefined(p);
  a.median_recall = medianOfDefined(r);
  a.median_iou = medianOfDefined(j);
  return a;
}

nlohmann::json toJson(const MaskAccuracy& a) {
  auto number = [](double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); };
  return {{"frames", a.frames},
          {"frames_with_truth", a.frames_with_truth},
          {"precision", number(a.precision)},
          {"recall", number(a.recall)},
          {"iou", number(a.iou)},
          {"dynamic_fraction", number(a.dynamic_fraction)},
          {"median_precision", number(a.median_precision)},
          {"median_recall", number(a.median_recall)},
          {"median_iou", number(a.median_iou)},
          {"true_positive", a.total.true_positive},
          {"false_positive", a.total.false_positive},
          {"false_negative", a.total.false_negative}};
}

}  // namespace amos::eval
