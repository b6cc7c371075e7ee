#pragma once
// Reading a recorded RGB-D sequence in the TUM RGB-D / Bonn layout (rgb/ depth/ rgb.txt depth.txt, or an
// associations.txt), with the frame association `amos-slam run` uses: RGB and depth images paired by nearest time
// stamp within 20 ms, or as the association file lists them; or a ROS 1 bag (a path ending in ".bag"), read as
// `amos-slam run --sequence X.bag` reads it (docs/ros.md: topics, pairing by header stamp, ground truth from a
// groundtruth.txt beside it or a topic). For programs that replay a recording through amos::Slam
// (examples/cpp/track_folder.cc); a camera program needs none of it.
//
//   amos::SequenceFolder folder("data/rgbd_dataset_freiburg2_desk");   // or "fr2_desk.bag"
//   while (const std::optional<amos::RgbdImages> f = folder.next()) slam.track(f->bgr, f->depth, f->timestamp);
//   if (folder.skipped() > 0) ...;   // frames that could not be read, each warned about in the log
//
//   amos::SequenceOptions o;  o.groundtruth_topic = "/tf";   // the TUM bags' /world -> /kinect
//   amos::SequenceFolder bag("rgbd_dataset_freiburg1_xyz.bag", o);
//
// Bags are read only by a library built with the ROS part (bagReadingAvailable(); AMOS_WITH_ROS): otherwise a
// ".bag" path is an error naming it. Errors (a folder that is not a sequence, a malformed list, a bag that cannot be
// read or lacks a topic, read(i) of a frame that cannot be read, a moved-from folder): std::runtime_error naming
// the file (and line, or the bag's topic). Every member function may be called from any thread (the calls are
// serialised).
#include <opencv2/core.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "amos/slam.h"

namespace amos {

// How a bag is read. For a folder every member must be left as it is (an error naming it otherwise).
struct SequenceOptions {
  // The colour and depth sensor_msgs/Image topics and the CameraInfo topic ("" = the first known driver's names
  // that the bag has: TUM RGB-D, openni2_launch, realsense2_camera; docs/ros.md).
  std::string rgb_topic, depth_topic, camera_info_topic;
  // The ground truth from this topic (geometry_msgs/PoseStamped, geometry_msgs/TransformStamped, nav_msgs/Odometry
  // or tf2_msgs/TFMessage) instead of a groundtruth.txt beside the bag ("" = that file, when there is one).
  std::string groundtruth_topic;
  // For a tf2_msgs/TFMessage ground-truth topic: the transform from this frame to that one (the TUM bags' names).
  std::string groundtruth_parent_frame = "/world", groundtruth_child_frame = "/kinect";
};

// Whether this library reads ROS 1 bags (built with the ROS part, AMOS_WITH_ROS).
bool bagReadingAvailable();

// One frame of a folder, as read from its files.
struct RgbdImages {
  cv::Mat bgr;            // CV_8UC3, OpenCV's BGR order
  // As stored: CV_16UC1 raw values (metres = value / DepthMapFactor); from a bag's 32FC1 topic CV_32FC1 metres.
  cv::Mat depth;
  double timestamp = 0;   // of the RGB image, seconds
  std::string rgb_file;   // the colour image's file (a bag's: "<bag>:<topic>/<stamp>.png")
  std::string depth_file; // the depth image's file (likewise)
};

// A TUM/Bonn-layout folder or a bag. Move-only; a moved-from one throws std::runtime_error from every member
// function.
class SequenceFolder {
 public:
  // Indexes the folder (reads its lists) or the bag (reads its stamps, checks every image message's type and
  // encoding, and reads the ground-truth topic); the images are read by read() and next().
  explicit SequenceFolder(const std::string& path, const SequenceOptions& options = {});
  ~SequenceFolder();
  SequenceFolder(SequenceFolder&&) noexcept;
  SequenceFolder& operator=(SequenceFolder&&) noexcept;

  // The associated frames whose files exist.
  std::size_t size() const;
  // Frame i (0-based), read from its files; an unreadable frame is an error naming its file.
  RgbdImages read(std::size_t i) const;
  // The frames in order, from the first, decoded ahead by a thread of the folder's own (as `amos-slam run` reads
  // a folder), so that reading overlaps with tracking; nullopt after the last. A frame that cannot be read (missing,
  // truncated, not an image, the wrong type, its two images of different sizes) is skipped, as `amos-slam run`
  // skips it: one warning in the log naming the file and the reason, and counted in skipped(). Independent of
  // read(i).
  std::optional<RgbdImages> next();
  // Frames next() skipped so far (the frames whose files do not exist are not counted in size() at all).
  std::size_t skipped() const;
  // The sequence's ground truth file ("" when it has none, or a bag's comes from SequenceOptions::groundtruth_topic).
  std::string groundTruthFile() const;
  // The ground truth's poses (T_wc of the camera in the ground truth's world, as recorded), from the file or the
  // topic; empty when there is none. A file that cannot be read is an error naming it and the line.
  std::vector<StampedPose> groundTruth() const;
  // Whether it is a bag.
  bool isBag() const;
  // The folder or bag, as given.
  std::string dir() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amos
