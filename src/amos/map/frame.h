#pragma once
// One RGB-D frame as tracking sees it: undistorted ORB keypoints with depth and virtual right coordinate
// (u_r = u - bf / z, ORB-SLAM2's RGB-D convention), a grid index for area queries, and the per-frame tracking
// state (pose, map-point matches, outlier flags). A Frame belongs to the tracking thread; its features are
// immutable and shared with the keyframe made from it.
#include <opencv2/core.hpp>

#include <memory>
#include <vector>

#include "amos/core/pose.h"
#include "amos/feature/keypoint_grid.h"
#include "amos/map/ids.h"
#include "amos/map/sensor.h"

namespace amos::map {

class MapPoint;

// The pose with its rotation projected back onto SO(3). Poses that are composed again and again (motion model:
// T_next = T_k * T_{k-1}^-1 * T_k) must be re-orthonormalised: Isometry3d::inverse() transposes the rotation, so
// round-off in its scale would otherwise grow geometrically from frame to frame.
core::SE3 orthonormalized(const core::SE3& T);

struct FrameFeatures {
  std::vector<cv::KeyPoint> keys;  // undistorted, level-0 pixels; octave = pyramid level
  cv::Mat descriptors;             // N x 32 CV_8U
  std::vector<float> depth;        // metres; <= 0 where the depth image has none
  std::vector<float> u_right;      // virtual right coordinate; < 0 where there is no depth
  feature::KeypointGrid grid;      // over `keys`

  std::size_t size() const { return keys.size(); }
  bool hasDepth(int i) const { return depth[i] > 0; }
};

struct FrameBuildStats {
  int extracted = 0;         // keypoints delivered by the extractor
  int removed_dynamic = 0;   // dropped because they fall inside the dynamic mask
  int with_depth = 0;
};

// Builds the features of a frame from the extractor's output (distorted keypoints, descriptors), the depth image
// (CV_32F metres, registered to the colour image) and an optional dynamic mask (CV_8U, 255 = dynamic, same size
// as the image): masked keypoints are dropped here, before any matching, so they never reach the map.
std::shared_ptr<FrameFeatures> buildFrameFeatures(const Sensor& sensor, const std::vector<cv::KeyPoint>& raw_keys,
                                                  const cv::Mat& descriptors, const cv::Mat& depth,
                                                  const cv::Mat& dynamic_mask, FrameBuildStats* stats = nullptr);

// A small blurred, zero-mean copy of the grey image (PTAM-style) used to rank keyframes for relocalisation.
cv::Mat makeThumbnail(const cv::Mat& gray);
// Zero-mean sum of squared differences of two thumbnails (smaller = more similar).
double thumbnailDistance(const cv::Mat& a, const cv::Mat& b);

struct Frame {
  FrameId id = 0;
  double timestamp = 0;
  std::shared_ptr<const Sensor> sensor;
  std::shared_ptr<const FrameFeatures> features;
  cv::Mat thumbnail;
  cv::Mat dynamic_mask;  // kept (may be empty) to count map points projecting onto dynamic pixels
  cv::Mat depth_image;   // CV_32F metres: tells points on a mover from points behind it; the keyframe's template
  cv::Mat gray;          // CV_8U, the grey image the features were detected in (photometric refinement)

  core::SE3 T_cw = core::SE3::Identity();
  bool has_pose = false;
  std::vector<std::shared_ptr<MapPoint>> map_points;  // per keypoint, null = unmatched
  std::vector<bool> outlier;                          // per keypoint, set by pose optimisation
  KeyFrameId reference_kf = kNoKeyFrame;

  std::size_t size() const { return features ? features->size() : 0; }
  void setPose(const core::SE3& T) {
    T_cw = orthonormalized(T);
    has_pose = true;
  }
  Eigen::Vector3d center() const { return T_cw.inverse().translation(); }
  void resetMatches();  // clears map points and outlier flags
  // World point of keypoint i from its depth (requires depth and a pose).
  Eigen::Vector3d unproject(int i) const;
};

// Makes a frame (no pose, no matches) around built features.
Frame makeFrame(FrameId id, double timestamp, std::shared_ptr<const Sensor> sensor,
                std::shared_ptr<const FrameFeatures> features, cv::Mat thumbnail, cv::Mat dynamic_mask);

}  // namespace amos::map
