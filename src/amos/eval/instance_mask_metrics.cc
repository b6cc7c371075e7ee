#include "amos/eval/instance_mask_metrics.h"

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "amos/core/error.h"

namespace amos::eval {

std::vector<InstanceFrameCounts> compareInstanceMasks(const cv::Mat& predicted, const cv::Mat& instances,
                                                      const std::vector<bool>& moving) {
  core::require(predicted.type() == CV_8UC1 && instances.type() == CV_16UC1,
                "compareInstanceMasks: predicted must be CV_8U, instances CV_16U");
  core::require(predicted.size() == instances.size(), "compareInstanceMasks: masks differ in size");
  auto isMoving = [&](std::uint16_t id) { return id != 0 && id < moving.size() && moving[id]; };
  cv::Mat components;
  const int count = cv::connectedComponents(predicted != 0, components, 8, CV_32S);
  // Per component: static pixels, and its overlap with each moving instance.
  std::vector<std::int64_t> component_static(count, 0);
  std::vector<std::map<std::uint16_t, std::int64_t>> overlap(count);
  std::map<std::uint16_t, InstanceFrameCounts> per_id;
  for (int y = 0; y < predicted.rows; ++y) {
    const uchar* p = predicted.ptr<uchar>(y);
    const std::uint16_t* id = instances.ptr<std::uint16_t>(y);
    const int* c = components.ptr<int>(y);
    for (int x = 0; x < predicted.cols; ++x) {
      if (id[x] != 0) {
        InstanceFrameCounts& counts = per_id[id[x]];
        ++counts.pixels;
        if (p[x] != 0) {
          ++counts.marked;
          if (isMoving(id[x])) ++overlap[c[x]][id[x]];
        }
      } else if (p[x] != 0) {
        ++component_static[c[x]];
      }
    }
  }
  for (auto& [id, counts] : per_id) counts.id = id, counts.moving = isMoving(id);
  for (int k = 1; k < count; ++k) {
    if (component_static[k] == 0 || overlap[k].empty()) continue;
    std::uint16_t best = 0;
    std::int64_t best_overlap = 0;
    for (const auto& [id, n] : overlap[k])
      if (n > best_overlap) best = id, best_overlap = n;  // map order: ties go to the lower id
    per_id[best].attributed_fp += component_static[k];
  }
  std::vector<InstanceFrameCounts> out;
  out.reserve(per_id.size());
  for (const auto& [id, counts] : per_id) out.push_back(counts);
  return out;
}

void InstanceAccuracyAccumulator::describe(std::uint16_t id, std::string category, std::string name) {
  Track& t = tracks_[id];
  t.acc.id = id;
  t.acc.category = std::move(category);
  t.acc.name = std::move(name);
}

void InstanceAccuracyAccumulator::add(int frame, const cv::Mat& predicted, const cv::Mat& instances,
                                      const std::vector<bool>& moving) {
  ++frames_;
  for (const InstanceFrameCounts& c : compareInstanceMasks(predicted, instances, moving)) {
    Track& t = tracks_[c.id];
    InstanceAccuracy& a = t.acc;
    a.id = c.id;
    if (c.moving) {
      if (t.pending_stop >= 0) a.releases.emplace_back(t.pending_stop, -1);
      t.pending_stop = -1;
      ++a.moving_frames;
      a.moving_pixels += c.pixels;
      a.moving_marked += c.marked;
      a.attributed_fp += c.attributed_fp;
    } else {
      if (t.was_moving) t.pending_stop = frame;
      ++a.rest_frames;
      a.rest_pixels += c.pixels;
      a.rest_marked += c.marked;
      if (t.pending_stop >= 0 && c.marked < kReleasedFraction * c.pixels) {
        a.releases.emplace_back(t.pending_stop, frame - t.pending_stop);
        t.pending_stop = -1;
      }
    }
    t.was_moving = c.moving;
  }
}

std::vector<InstanceAccuracy> InstanceAccuracyAccumulator::summary() const {
  auto ratio = [](std::int64_t num, std::int64_t den) {
    return den > 0 ? static_cast<double>(num) / static_cast<double>(den) : InstanceAccuracy::kNaN;
  };
  std::vector<InstanceAccuracy> out;
  for (const auto& [id, t] : tracks_) {
    InstanceAccuracy a = t.acc;
    if (t.pending_stop >= 0) a.releases.emplace_back(t.pending_stop, -1);
    a.recall = ratio(a.moving_marked, a.moving_pixels);
    a.precision = ratio(a.moving_marked, a.moving_marked + a.attributed_fp);
    a.rest_marked_fraction = ratio(a.rest_marked, a.rest_pixels);
    out.push_back(std::move(a));
  }
  return out;
}

nlohmann::json toJson(const std::vector<InstanceAccuracy>& accuracy) {
  auto number = [](double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); };
  nlohmann::json list = nlohmann::json::array();
  for (const InstanceAccuracy& a : accuracy) {
    nlohmann::json releases = nlohmann::json::array();
    for (const auto& [first, frames] : a.releases)
      releases.push_back({{"first_rest_frame", first}, {"frames_to_release", frames}});
    list.push_back({{"id", a.id},
                    {"class", a.category},
                    {"name", a.name},
                    {"moving_frames", a.moving_frames},
                    {"rest_frames", a.rest_frames},
                    {"recall", number(a.recall)},
                    {"precision", number(a.precision)},
                    {"rest_marked_fraction", number(a.rest_marked_fraction)},
                    {"releases", releases}});
  }
  return list;
}

}  // namespace amos::eval
