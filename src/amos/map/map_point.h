#pragma once
// A 3D landmark. Owned by the Map (shared_ptr); it refers to the keyframes that observe it by id.
//
// Thread-safety contract: everything except the id and the atomic counters is guarded by Map::mutex(): read it
// under a shared lock, change it under an exclusive lock (the Map's graph operations take care of the
// observation bookkeeping on both sides). The visible/found/dynamic counters are atomics that tracking bumps
// while holding only a shared lock.
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <atomic>
#include <map>
#include <memory>

#include "amos/map/ids.h"

namespace amos::map {

class Sensor;

class MapPoint {
 public:
  MapPoint(MapPointId id, const Eigen::Vector3d& position_w, KeyFrameId reference_kf, FrameId first_frame);

  MapPointId id() const { return id_; }
  FrameId firstFrame() const { return first_frame_; }
  KeyFrameId firstKeyFrame() const { return first_kf_; }

  // --- guarded by Map::mutex() ---
  const Eigen::Vector3d& position() const { return position_; }
  void setPosition(const Eigen::Vector3d& p) { position_ = p; }

  // keyframe id -> keypoint index in that keyframe.
  const std::map<KeyFrameId, int>& observations() const { return observations_; }
  // Observation count as ORB-SLAM2 counts it: an observation with depth counts twice (it constrains the point
  // like a stereo pair).
  int numObservations() const { return num_obs_; }
  bool isObservedBy(KeyFrameId kf) const { return observations_.count(kf) > 0; }
  int indexIn(KeyFrameId kf) const;
  void addObservation(KeyFrameId kf, int index, bool with_depth);
  // Returns true when the keyframe was an observer.
  bool eraseObservation(KeyFrameId kf, bool with_depth);

  const cv::Mat& descriptor() const { return descriptor_; }  // 1 x 32 CV_8U
  void setDescriptor(const cv::Mat& d) { d.copyTo(descriptor_); }

  // Mean viewing direction (unit, world) and the distance range in which ORB can detect the point.
  const Eigen::Vector3d& normal() const { return normal_; }
  double minDistance() const { return 0.8 * min_distance_; }
  double maxDistance() const { return 1.2 * max_distance_; }
  void setNormalAndDistances(const Eigen::Vector3d& normal, double min_d, double max_d);
  // The distances as given to setNormalAndDistances (without the margins above), to save and restore a point.
  double minDistanceUnpadded() const { return min_distance_; }
  double maxDistanceUnpadded() const { return max_distance_; }
  // Pyramid level at which a keypoint of this point is expected at distance `dist`.
  int predictScale(double dist, const Sensor& sensor) const;

  KeyFrameId referenceKeyFrame() const { return reference_kf_; }
  void setReferenceKeyFrame(KeyFrameId kf) { reference_kf_ = kf; }

  bool isBad() const { return bad_; }
  void setBadFlag() { bad_ = true; }
  // When fused into another point: the survivor (nullptr otherwise).
  std::shared_ptr<MapPoint> replacedBy() const { return replaced_by_.lock(); }
  void setReplacedBy(const std::shared_ptr<MapPoint>& p) { replaced_by_ = p; }

  // --- atomic tracking statistics ---
  void increaseVisible(int n = 1) { visible_.fetch_add(n, std::memory_order_relaxed); }
  void increaseFound(int n = 1) { found_.fetch_add(n, std::memory_order_relaxed); }
  int visible() const { return visible_.load(std::memory_order_relaxed); }
  int found() const { return found_.load(std::memory_order_relaxed); }
  double foundRatio() const { return static_cast<double>(found()) / std::max(1, visible()); }
  // How often the point projected into a frame's dynamic mask (hook for culling points on moving objects).
  void increaseDynamicHits(int n = 1) { dynamic_hits_.fetch_add(n, std::memory_order_relaxed); }
  int dynamicHits() const { return dynamic_hits_.load(std::memory_order_relaxed); }
  // Frames in which the point was projected while a dynamic mask was given (the denominator of the ratio).
  void increaseMaskedViews(int n = 1) { masked_views_.fetch_add(n, std::memory_order_relaxed); }
  int maskedViews() const { return masked_views_.load(std::memory_order_relaxed); }
  void addCountersFrom(const MapPoint& other);

 private:
  const MapPointId id_;
  const FrameId first_frame_;
  const KeyFrameId first_kf_;
  Eigen::Vector3d position_;
  std::map<KeyFrameId, int> observations_;
  int num_obs_ = 0;
  cv::Mat descriptor_;
  Eigen::Vector3d normal_ = Eigen::Vector3d::Zero();
  double min_distance_ = 0, max_distance_ = 0;
  KeyFrameId reference_kf_;
  bool bad_ = false;
  std::weak_ptr<MapPoint> replaced_by_;
  std::atomic<int> visible_{1}, found_{1}, dynamic_hits_{0}, masked_views_{0};
};

using MapPointPtr = std::shared_ptr<MapPoint>;

}  // namespace amos::map
