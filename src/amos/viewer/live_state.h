#pragma once
// What the viewer shows, held once for every browser: the map points (and those culled as dynamic), keyframes,
// trajectory, ground truth, the dense layers, the current frame's status and image; and the recent updates as numbered events, so a
// browser that loaded the whole state (stateJson, with its "seq") receives only what changed after it
// (eventsAfter). The events are a bounded ring: a browser that falls behind by more than it holds is told to
// reload the whole state instead of slowing anyone down.
//
// Thread-safe: the publisher applies updates, the server's threads read. eventsAfter waits on a condition
// variable (at most `timeout`), never the publisher.
#include <nlohmann/json.hpp>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "amos/viewer/live_update.h"
#include "amos/viewer/ply_file.h"

namespace amos::viewer {

struct EventBatch {
  std::vector<std::pair<std::uint64_t, std::string>> events;  // (seq, JSON), oldest first
  bool reload = false;  // `after` is older than the ring: fetch the whole state again
  bool closed = false;  // the viewer is shutting down: end the stream
};

class LiveState {
 public:
  explicit LiveState(std::size_t max_events = 512, std::size_t max_culled = 100000);

  void apply(const LiveUpdate& update);
  void setFrameImage(std::vector<unsigned char> jpeg);
  // Latest frame image (JPEG), null before the first.
  std::shared_ptr<const std::vector<unsigned char>> frameImage() const;
  // Files of a finished run that the page may show (`view`: overlays/...); replaces.
  void setFiles(nlohmann::json files);
  // A dense product (dense_layer.h: "live" the growing cloud of a run, "mesh", "cloud", "removed" of a finished
  // one), replacing the layer of that name; the browsers are told its new version and fetch it
  // (/api/dense/NAME.bin). Encodes outside the lock; throws core::Error on inconsistent sizes.
  void setDenseLayer(const std::string& name, const ColouredGeometry& geometry);
  // The layer's encoded block, null when there is none.
  std::shared_ptr<const std::string> denseLayer(const std::string& name) const;

  // Everything, with "seq" = the last event it includes.
  nlohmann::json stateJson() const;
  std::uint64_t seq() const;
  EventBatch eventsAfter(std::uint64_t after, std::chrono::milliseconds timeout) const;
  // Ends every waiting and future eventsAfter (closed).
  void close();

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::size_t max_events_, max_culled_;
  std::uint64_t seq_ = 0;
  bool closed_ = false;
  std::deque<std::pair<std::uint64_t, std::string>> events_;
  std::map<std::uint64_t, PointSample> points_, culled_;
  std::map<std::uint64_t, KeyFrameSample> keyframes_;
  std::vector<TrajectoryPoint> trajectory_, ground_truth_;
  nlohmann::json info_ = nlohmann::json::object(), frame_, summary_, files_ = nlohmann::json::array();
  std::shared_ptr<const std::vector<unsigned char>> frame_image_;
  struct DenseLayer {
    std::shared_ptr<const std::string> data;
    nlohmann::json meta;  // {version, vertices, triangles}: what stateJson and the events say of it
  };
  std::map<std::string, DenseLayer> dense_;
  std::uint64_t dense_version_ = 0;
  void pushEvent(const nlohmann::json& event);  // under mutex_
};

}  // namespace amos::viewer
