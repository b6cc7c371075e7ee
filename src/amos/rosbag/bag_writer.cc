#include "amos/rosbag/bag_writer.h"

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <rosbag/bag.h>

#include "amos/core/error.h"
#include "amos/io/png_reader.h"
#include "amos/rosbag/image_messages.h"

namespace amos::rosbag {

namespace {

::rosbag::compression::CompressionType compressionOf(const std::string& name) {
  if (name == "bz2") return ::rosbag::compression::BZ2;
  if (name == "lz4") return ::rosbag::compression::LZ4;
  return ::rosbag::compression::Uncompressed;
}

cv::Mat readImageFile(const std::string& file, int flags) {
  const cv::Mat image = io::readPng(file, flags);
  core::require(!image.empty(), fmt::format("writing a bag: cannot read '{}'", file));
  return image;
}

}  // namespace

void BagWriteOptions::check() const {
  core::require(compression == "none" || compression == "bz2" || compression == "lz4",
                fmt::format("bag compression '{}': expected none, bz2 or lz4", compression));
  core::require(colour_encoding == "rgb8" || colour_encoding == "bgr8",
                fmt::format("bag colour encoding '{}': expected rgb8 or bgr8", colour_encoding));
  core::require(depth_encoding == "16UC1" || depth_encoding == "32FC1",
                fmt::format("bag depth encoding '{}': expected 16UC1 or 32FC1", depth_encoding));
  core::require(depth_factor > 0, fmt::format("bag depth factor {} must be positive", depth_factor));
}

void writeBag(const io::SequenceIndex& sequence, const std::string& bag, const BagWriteOptions& options) {
  options.check();
  ::rosbag::Bag writer;
  try {
    writer.open(bag, ::rosbag::bagmode::Write);
    writer.setCompression(compressionOf(options.compression));
    for (const io::AssociatedFrame& f : sequence.frames) {
      ros::Time rgb_stamp, depth_stamp;
      rgb_stamp.fromSec(f.t_rgb);
      depth_stamp.fromSec(f.t_depth);
      cv::Mat colour = readImageFile(f.rgb_file, cv::IMREAD_COLOR);
      if (options.colour_encoding == "rgb8") cv::cvtColor(colour, colour, cv::COLOR_BGR2RGB);
      writer.write(options.topics.rgb, rgb_stamp,
                   imageMessage(colour, options.colour_encoding, rgb_stamp, options.frame_id));
      cv::Mat depth = readImageFile(f.depth_file, cv::IMREAD_UNCHANGED);
      if (options.depth_encoding == "32FC1") depth.convertTo(depth, CV_32F, 1.0 / options.depth_factor);
      writer.write(options.topics.depth, depth_stamp,
                   imageMessage(depth, options.depth_encoding, depth_stamp, options.frame_id));
      if (options.camera && !options.topics.camera_info.empty())
        writer.write(options.topics.camera_info, rgb_stamp,
                     cameraInfoMessage(*options.camera, rgb_stamp, options.frame_id));
    }
    writer.close();
  } catch (const ::rosbag::BagException& e) {
    throw core::Error(fmt::format("bag '{}' cannot be written: {}", bag, e.what()));
  }
}

}  // namespace amos::rosbag
