#include "amos/dynamic/prior_propagation.h"

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/segmentation/segment_masks.h"

namespace amos::dynamic {

void PriorScheduleOptions::check() const {
  core::requireAtLeast(interval, "interval", 1);
  core::requireAtLeast(lag, "lag", 0);
  core::requireOption(
      lag <= interval, core::option(lag, "lag"),
      fmt::format("({}) must not exceed interval ({}): a segmentation would then be needed before the one "
                  "of the frame it replaces is used",
                  lag, interval),
      {core::option(interval, "interval")});
  core::requireAtLeast(detect_every, "detect_every", 1);
  core::requireAtLeast(hold_missed, "hold_missed", 0);
  core::requireAtLeast(min_tracks, "min_tracks", 1);
}

std::size_t PriorScheduleOptions::baseFor(std::size_t frame) const {
  const std::size_t l = static_cast<std::size_t>(lag), n = static_cast<std::size_t>(interval);
  if (frame < l) return 0;
  return (frame - l) / n * n;
}

namespace {

float median(std::vector<float>& v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

cv::Point offsetPixels(const cv::Point2f& offset) {
  return {static_cast<int>(std::lround(offset.x)), static_cast<int>(std::lround(offset.y))};
}

}  // namespace

PriorMaskPropagator::PriorMaskPropagator(cv::Size image_size, segmentation::MaskDilationOptions dilation,
                                         PriorScheduleOptions options)
    : size_(image_size), dilation_(std::move(dilation)), options_(options) {
  dilation_.check();
  options_.check();
}

void PriorMaskPropagator::reset(const std::vector<segmentation::SegmentedInstance>& instances) {
  // Carried instances that no new one overlaps: missed by the network this time (kept a while) or gone.
  std::vector<Moving> held;
  for (Moving& m : instances_) {
    if (m.missed >= options_.hold_missed) continue;
    const cv::Rect moved = m.instance.box + offsetPixels(m.offset);
    const bool found = std::any_of(instances.begin(), instances.end(), [&](const auto& s) {
      const double overlap = (moved & s.box).area();
      return overlap > 0.3 * std::min(moved.area(), s.box.area());
    });
    if (found) continue;
    ++m.missed;
    held.push_back(std::move(m));
  }
  instances_.clear();
  age_ = 0;
  const cv::Mat kernel = segmentation::dilationKernel(dilation_);
  const int half = kernel.empty() ? 0 : kernel.cols / 2;
  for (const segmentation::SegmentedInstance& instance : instances) {
    if (instance.mask.empty() || instance.box.empty()) continue;
    Moving m;
    m.instance = instance;
    m.dilated_box = cv::Rect(instance.box.x - half, instance.box.y - half, instance.box.width + 2 * half,
                             instance.box.height + 2 * half);
    // Dilating each instance on its own gives the dilation of the union (dilation distributes over union).
    cv::copyMakeBorder(instance.mask, m.dilated, half, half, half, half, cv::BORDER_CONSTANT, cv::Scalar(0));
    // segmentation::dilateMask: what cv::dilate gives with this kernel, by its row runs (a few passes instead of
    // one per kernel element).
    if (!kernel.empty()) m.dilated = segmentation::dilateMask(m.dilated, dilation_);
    instances_.push_back(std::move(m));
  }
  for (Moving& m : held) instances_.push_back(std::move(m));
}

bool PriorMaskPropagator::inside(const Moving& m, const cv::Point2f& p) const {
  const cv::Point shift = offsetPixels(m.offset);
  const int x = static_cast<int>(std::floor(p.x)) - shift.x - m.instance.box.x;
  const int y = static_cast<int>(std::floor(p.y)) - shift.y - m.instance.box.y;
  if (x < 0 || y < 0 || x >= m.instance.box.width || y >= m.instance.box.height) return false;
  return m.instance.mask.at<std::uint8_t>(y, x) != 0;
}

void PriorMaskPropagator::step(const FrameFlow& flow) {
  ++age_;
  std::vector<float> dx, dy;
  for (Moving& m : instances_) {
    dx.clear();
    dy.clear();
    for (const PointTrack& t : flow.tracks) {
      if (!inside(m, t.last)) continue;
      dx.push_back(t.current.x - t.last.x);
      dy.push_back(t.current.y - t.last.y);
    }
    if (static_cast<int>(dx.size()) >= options_.min_tracks) m.velocity = {median(dx), median(dy)};
    m.offset += m.velocity;
  }
}

cv::Mat PriorMaskPropagator::paint(bool dilated) const {
  std::vector<segmentation::SegmentedInstance> moved;
  moved.reserve(instances_.size());
  for (const Moving& m : instances_) {
    segmentation::SegmentedInstance s;
    s.box = (dilated ? m.dilated_box : m.instance.box) + offsetPixels(m.offset);
    s.mask = dilated ? m.dilated : m.instance.mask;
    moved.push_back(std::move(s));
  }
  return segmentation::paintInstances(moved, size_);
}

cv::Mat PriorMaskPropagator::mask() const { return paint(false); }
cv::Mat PriorMaskPropagator::dilatedMask() const { return paint(true); }

}  // namespace amos::dynamic
