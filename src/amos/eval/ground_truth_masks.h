#pragma once
// Ground-truth mover masks of a sequence that has them (the synthetic sequences written by `amos-slam synth`):
//   masks.txt       `timestamp masks/<stamp>.png`, one line per frame in frame order (line k = frame k)
//   masks/*.png     16-bit instance ids, 0 = static scene
//   instances.json  {"instances": {"<id>": {"class", "name", "moving_frames": [[first, last], ...]}}}
// The truth for a frame is the union of the instances that move in that frame: an object at rest (the box before
// it is pushed) is static scene for SLAM and for the front end, which can only see motion.
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace amos::eval {

struct GroundTruthInstance {
  std::uint16_t id = 0;
  std::string category;  // "person" or "object"
  std::string name;
  std::vector<std::pair<int, int>> moving_frames;  // inclusive frame ranges
  bool movingAt(int frame) const;
};

class GroundTruthMasks {
 public:
  // The sequence's ground-truth masks, or nullopt when `sequence_dir` has no masks.txt and instances.json.
  // Throws core::Error when they exist but are malformed.
  static std::optional<GroundTruthMasks> find(const std::string& sequence_dir);
  GroundTruthMasks(const std::string& masks_index, const std::string& instances_json);

  std::size_t size() const { return files_.size(); }
  const std::vector<GroundTruthInstance>& instances() const { return instances_; }
  // The frame whose mask time stamp lies nearest to t within max_dt seconds, or nullopt.
  std::optional<int> frameAt(double t, double max_dt = 0.005) const;
  // CV_16U instance ids of a frame; throws core::Error naming the file when it cannot be read.
  cv::Mat instanceMask(int frame) const;
  // CV_8U, 255 on the instances moving in that frame.
  cv::Mat moverMask(int frame) const;
  // Per instance id (index), whether it moves in that frame (ids without an instance: false).
  std::vector<bool> movingIds(int frame) const;
  // CV_8U, 255 where `instances` (CV_16U ids) holds an id with moving[id].
  static cv::Mat moverMask(const cv::Mat& instances, const std::vector<bool>& moving);

 private:
  std::vector<double> stamps_;     // sorted as in masks.txt
  std::vector<std::string> files_; // absolute paths
  std::vector<GroundTruthInstance> instances_;
};

}  // namespace amos::eval
