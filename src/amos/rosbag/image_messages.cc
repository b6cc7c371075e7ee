#include "amos/rosbag/image_messages.h"

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstring>

#include "amos/core/error.h"

namespace amos::rosbag {

namespace {

struct Layout {
  int type;                // of one pixel in the message
  int colour_conversion;   // to BGR, -1 = none
};

// The cv::Mat type of the colour encodings this reader takes, or nothing.
bool colourLayout(const std::string& encoding, Layout& layout) {
  if (encoding == "bgr8") layout = {CV_8UC3, -1};
  else if (encoding == "rgb8") layout = {CV_8UC3, cv::COLOR_RGB2BGR};
  else if (encoding == "bgra8") layout = {CV_8UC4, cv::COLOR_BGRA2BGR};
  else if (encoding == "rgba8") layout = {CV_8UC4, cv::COLOR_RGBA2BGR};
  else if (encoding == "mono8") layout = {CV_8UC1, cv::COLOR_GRAY2BGR};
  else return false;
  return true;
}

bool depthLayout(const std::string& encoding, Layout& layout) {
  if (encoding == "16UC1" || encoding == "mono16") layout = {CV_16UC1, -1};
  else if (encoding == "32FC1") layout = {CV_32FC1, -1};
  else return false;
  return true;
}

// The message's pixels as a cv::Mat over its buffer (not a copy), after checking that the buffer holds them.
cv::Mat view(const sensor_msgs::Image& msg, int type, const std::string& where) {
  core::require(!msg.is_bigendian || CV_ELEM_SIZE1(type) == 1,
                fmt::format("{}: big-endian {} images are not read", where, msg.encoding));
  const std::size_t row_bytes = static_cast<std::size_t>(msg.width) * CV_ELEM_SIZE(type);
  core::require(msg.width > 0 && msg.height > 0 && msg.step >= row_bytes &&
                    msg.data.size() >= static_cast<std::size_t>(msg.step) * msg.height,
                fmt::format("{}: a {}x{} {} image with step {} does not fit its {} bytes", where, msg.width,
                            msg.height, msg.encoding, msg.step, msg.data.size()));
  // cv::Mat does not write through this pointer here: every caller copies or converts into a new buffer.
  auto* data = const_cast<std::uint8_t*>(msg.data.data());
  return cv::Mat(static_cast<int>(msg.height), static_cast<int>(msg.width), type, data, msg.step);
}

}  // namespace

bool isColourEncoding(const std::string& encoding) {
  Layout layout{};
  return colourLayout(encoding, layout);
}

bool isDepthEncoding(const std::string& encoding) {
  Layout layout{};
  return depthLayout(encoding, layout);
}

cv::Mat colourImage(const sensor_msgs::Image& msg, const std::string& where) {
  Layout layout{};
  core::require(colourLayout(msg.encoding, layout),
                fmt::format("{}: colour image encoding '{}' is not read (rgb8, bgr8, rgba8, bgra8 or mono8)", where,
                            msg.encoding));
  const cv::Mat pixels = view(msg, layout.type, where);
  cv::Mat bgr;
  if (layout.colour_conversion < 0) pixels.copyTo(bgr);
  else cv::cvtColor(pixels, bgr, layout.colour_conversion);
  return bgr;
}

cv::Mat depthImage(const sensor_msgs::Image& msg, const std::string& where) {
  Layout layout{};
  core::require(depthLayout(msg.encoding, layout),
                fmt::format("{}: depth image encoding '{}' is not read (16UC1, mono16 or 32FC1)", where,
                            msg.encoding));
  return view(msg, layout.type, where).clone();
}

sensor_msgs::Image imageMessage(const cv::Mat& image, const std::string& encoding, const ros::Time& stamp,
                                const std::string& frame_id) {
  sensor_msgs::Image msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = frame_id;
  msg.encoding = encoding;
  msg.height = static_cast<std::uint32_t>(image.rows);
  msg.width = static_cast<std::uint32_t>(image.cols);
  msg.is_bigendian = 0;
  msg.step = static_cast<std::uint32_t>(image.cols * image.elemSize());
  msg.data.resize(static_cast<std::size_t>(msg.step) * image.rows);
  for (int r = 0; r < image.rows; ++r) std::memcpy(&msg.data[r * msg.step], image.ptr(r), msg.step);
  return msg;
}

core::CameraIntrinsics cameraIntrinsics(const sensor_msgs::CameraInfo& info) {
  core::CameraIntrinsics c;
  c.fx = info.K[0];
  c.fy = info.K[4];
  c.cx = info.K[2];
  c.cy = info.K[5];
  double* lens[] = {&c.k1, &c.k2, &c.p1, &c.p2, &c.k3};
  for (std::size_t i = 0; i < std::min<std::size_t>(5, info.D.size()); ++i) *lens[i] = info.D[i];
  c.width = static_cast<int>(info.width);
  c.height = static_cast<int>(info.height);
  return c;
}

sensor_msgs::CameraInfo cameraInfoMessage(const core::CameraIntrinsics& c, const ros::Time& stamp,
                                          const std::string& frame_id) {
  sensor_msgs::CameraInfo info;
  info.header.stamp = stamp;
  info.header.frame_id = frame_id;
  info.width = static_cast<std::uint32_t>(c.width);
  info.height = static_cast<std::uint32_t>(c.height);
  info.distortion_model = "plumb_bob";
  info.D = {c.k1, c.k2, c.p1, c.p2, c.k3};
  info.K = {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {c.fx, 0, c.cx, 0, 0, c.fy, c.cy, 0, 0, 0, 1, 0};
  return info;
}

}  // namespace amos::rosbag
