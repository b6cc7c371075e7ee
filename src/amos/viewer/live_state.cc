#include "amos/viewer/live_state.h"

#include "amos/viewer/delta_json.h"
#include "amos/viewer/dense_layer.h"

namespace amos::viewer {

LiveState::LiveState(std::size_t max_events, std::size_t max_culled)
    : max_events_(max_events), max_culled_(max_culled) {}

void LiveState::apply(const LiveUpdate& u) {
  std::string event;
  {
    std::lock_guard lock(mutex_);
    for (const PointSample& p : u.map.points) points_[p.id] = p;
    for (const std::uint64_t id : u.map.removed) points_.erase(id);
    for (const PointSample& p : u.map.culled)
      if (culled_.size() < max_culled_) culled_[p.id] = p;
    for (const KeyFrameSample& k : u.map.keyframes) keyframes_[k.id] = k;
    for (const std::uint64_t id : u.map.removed_keyframes) keyframes_.erase(id);
    if (u.trajectory_reset) trajectory_.clear();
    trajectory_.insert(trajectory_.end(), u.trajectory.begin(), u.trajectory.end());
    if (u.ground_truth) ground_truth_ = *u.ground_truth;
    if (u.info) info_ = *u.info;
    if (u.frame) frame_ = *u.frame;
    if (u.summary) summary_ = *u.summary;
    ++seq_;
    pushEvent(updateJson(u, seq_));
  }
  changed_.notify_all();
}

void LiveState::pushEvent(const nlohmann::json& event) {
  events_.emplace_back(seq_, event.dump());
  while (events_.size() > max_events_) events_.pop_front();
}

void LiveState::setDenseLayer(const std::string& name, const ColouredGeometry& geometry) {
  auto data = std::make_shared<const std::string>(encodeDenseLayer(geometry));
  {
    std::lock_guard lock(mutex_);
    nlohmann::json meta = {{"version", ++dense_version_},
                           {"vertices", geometry.vertexCount()},
                           {"triangles", geometry.triangleCount()}};
    dense_[name] = {std::move(data), meta};
    ++seq_;
    pushEvent({{"seq", seq_}, {"dense", {{name, std::move(meta)}}}});
  }
  changed_.notify_all();
}

std::shared_ptr<const std::string> LiveState::denseLayer(const std::string& name) const {
  std::lock_guard lock(mutex_);
  const auto it = dense_.find(name);
  return it == dense_.end() ? nullptr : it->second.data;
}

void LiveState::setFrameImage(std::vector<unsigned char> jpeg) {
  auto image = std::make_shared<const std::vector<unsigned char>>(std::move(jpeg));
  std::lock_guard lock(mutex_);
  frame_image_ = std::move(image);
}

std::shared_ptr<const std::vector<unsigned char>> LiveState::frameImage() const {
  std::lock_guard lock(mutex_);
  return frame_image_;
}

void LiveState::setFiles(nlohmann::json files) {
  std::lock_guard lock(mutex_);
  files_ = std::move(files);
}

nlohmann::json LiveState::stateJson() const {
  std::lock_guard lock(mutex_);
  nlohmann::json points = nlohmann::json::array(), culled = nlohmann::json::array(),
                 keyframes = nlohmann::json::array();
  for (const auto& [id, p] : points_) points.push_back(pointJson(p));
  for (const auto& [id, p] : culled_) culled.push_back(pointJson(p));
  for (const auto& [id, k] : keyframes_) keyframes.push_back(keyFrameJson(k));
  nlohmann::json dense = nlohmann::json::object();
  for (const auto& [name, layer] : dense_) dense[name] = layer.meta;
  return {{"seq", seq_},
          {"info", info_},
          {"frame", frame_},
          {"summary", summary_},
          {"points", std::move(points)},
          {"culled", std::move(culled)},
          {"keyframes", std::move(keyframes)},
          {"trajectory", trajectoryJson(trajectory_)},
          {"ground_truth", trajectoryJson(ground_truth_)},
          {"frame_image", frame_image_ != nullptr},
          {"files", files_},
          {"dense", std::move(dense)}};
}

std::uint64_t LiveState::seq() const {
  std::lock_guard lock(mutex_);
  return seq_;
}

EventBatch LiveState::eventsAfter(std::uint64_t after, std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  if (after > seq_) {  // a browser that knew another run (the server was restarted)
    EventBatch batch;
    batch.reload = true;
    return batch;
  }
  changed_.wait_for(lock, timeout, [&] { return closed_ || seq_ > after; });
  EventBatch batch;
  batch.closed = closed_;
  if (seq_ <= after) return batch;
  if (events_.empty() || events_.front().first > after + 1) {
    batch.reload = true;
    return batch;
  }
  for (const auto& e : events_)
    if (e.first > after) batch.events.push_back(e);
  return batch;
}

void LiveState::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
}

}  // namespace amos::viewer
