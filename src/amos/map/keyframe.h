#pragma once
// A keyframe: an immutable copy of a frame's features plus mutable pose, map-point associations and graph links.
//
// Thread-safety contract: id, timestamp, features(), sensor() and the thumbnail are immutable and may be read
// without a lock. Pose, map points, covisibility, spanning tree and the bad flag are guarded by Map::mutex():
// shared lock to read, exclusive lock to write.
#include <opencv2/core.hpp>

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "amos/core/pose.h"
#include "amos/map/frame.h"
#include "amos/map/ids.h"
#include "amos/map/map_point.h"

namespace amos::map {

// A relative pose to another keyframe measured apart from the keypoints (the dense photometric alignment of this
// keyframe's frame against its reference keyframe, tracking/photometric_refiner.h); bundle adjustment keeps it
// (mapping/bundle_adjustment.h BaRelativePose). information: about the left perturbation of T_kr.
struct PoseLink {
  KeyFrameId reference = kNoKeyFrame;
  core::SE3 T_kr = core::SE3::Identity();
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
};

class KeyFrame {
 public:
  KeyFrame(KeyFrameId id, const Frame& frame);

  KeyFrameId id() const { return id_; }
  FrameId frameId() const { return frame_id_; }
  double timestamp() const { return timestamp_; }
  const FrameFeatures& features() const { return *features_; }
  const std::shared_ptr<const FrameFeatures>& sharedFeatures() const { return features_; }
  const Sensor& sensor() const { return *sensor_; }
  const std::shared_ptr<const Sensor>& sharedSensor() const { return sensor_; }
  int size() const { return static_cast<int>(features_->size()); }
  const cv::Mat& thumbnail() const { return thumbnail_; }  // small blurred image for relocalisation ranking

  // --- guarded by Map::mutex() ---
  const core::SE3& T_cw() const { return T_cw_; }
  core::SE3 T_wc() const { return T_cw_.inverse(); }
  Eigen::Vector3d center() const { return T_cw_.inverse().translation(); }
  void setPose(const core::SE3& T_cw) { T_cw_ = orthonormalized(T_cw); }

  const std::vector<MapPointPtr>& mapPoints() const { return map_points_; }
  const MapPointPtr& mapPoint(int i) const { return map_points_[i]; }
  void setMapPoint(int i, MapPointPtr p) { map_points_[i] = std::move(p); }
  void clearMapPoint(int i) { map_points_[i].reset(); }
  // Good points with at least min_obs observations (any, when min_obs <= 0).
  int trackedMapPoints(int min_obs) const;
  // Median depth of the good map points in this view (-1 when there is none).
  double medianSceneDepth() const;

  // Covisibility: weight = number of shared map points (only links with weight >= threshold, or the best one).
  const std::map<KeyFrameId, int>& connectionWeights() const { return weights_; }
  int weight(KeyFrameId other) const;
  // Connected keyframes by decreasing weight (ties: smaller id first).
  const std::vector<std::pair<int, KeyFrameId>>& orderedConnections() const { return ordered_; }
  std::vector<KeyFrameId> bestCovisibles(std::size_t n) const;
  std::vector<KeyFrameId> covisiblesWithWeight(int min_weight) const;
  void setConnection(KeyFrameId other, int weight);  // updates the ordering
  void eraseConnection(KeyFrameId other);
  void setConnections(std::map<KeyFrameId, int> weights);

  // Spanning tree (for reference-keyframe-relative trajectories after culling).
  KeyFrameId parent() const { return parent_; }
  void setParent(KeyFrameId p) { parent_ = p; }
  const std::set<KeyFrameId>& children() const { return children_; }
  void addChild(KeyFrameId c) { children_.insert(c); }
  void eraseChild(KeyFrameId c) { children_.erase(c); }
  bool hasFirstConnection() const { return first_connection_done_; }
  void markFirstConnectionDone() { first_connection_done_ = true; }

  bool isBad() const { return bad_; }
  void setBadFlag() { bad_ = true; }

  const std::optional<PoseLink>& photometricLink() const { return photometric_link_; }
  void setPhotometricLink(PoseLink link) { photometric_link_ = std::move(link); }

 private:
  void reorder();

  const KeyFrameId id_;
  const FrameId frame_id_;
  const double timestamp_;
  const std::shared_ptr<const FrameFeatures> features_;
  const std::shared_ptr<const Sensor> sensor_;
  const cv::Mat thumbnail_;
  core::SE3 T_cw_;
  std::vector<MapPointPtr> map_points_;
  std::map<KeyFrameId, int> weights_;
  std::vector<std::pair<int, KeyFrameId>> ordered_;
  KeyFrameId parent_ = kNoKeyFrame;
  std::set<KeyFrameId> children_;
  bool first_connection_done_ = false;
  bool bad_ = false;
  std::optional<PoseLink> photometric_link_;
};

using KeyFramePtr = std::shared_ptr<KeyFrame>;

}  // namespace amos::map
