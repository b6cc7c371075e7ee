#include "amos/map/frame.h"

#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"
#include "amos/map/map_point.h"

namespace amos::map {

std::shared_ptr<FrameFeatures> buildFrameFeatures(const Sensor& sensor, const std::vector<cv::KeyPoint>& raw_keys,
                                                  const cv::Mat& descriptors, const cv::Mat& depth,
                                                  const cv::Mat& dynamic_mask, FrameBuildStats* stats) {
  core::require(depth.type() == CV_32F, "buildFrameFeatures: depth must be CV_32F metres");
  core::require(descriptors.rows == static_cast<int>(raw_keys.size()),
                "buildFrameFeatures: one descriptor row per keypoint expected");
  const bool masked = !dynamic_mask.empty();
  if (masked) {
    core::require(dynamic_mask.type() == CV_8U && dynamic_mask.size() == depth.size(),
                  "buildFrameFeatures: dynamic mask must be CV_8U and the size of the image");
  }
  // Drop keypoints on dynamic pixels first (the paper's front end: they take no part in tracking or mapping).
  std::vector<int> keep;
  keep.reserve(raw_keys.size());
  for (int i = 0; i < static_cast<int>(raw_keys.size()); ++i) {
    if (masked) {
      const int x = std::clamp(cvRound(raw_keys[i].pt.x), 0, dynamic_mask.cols - 1);
      const int y = std::clamp(cvRound(raw_keys[i].pt.y), 0, dynamic_mask.rows - 1);
      if (dynamic_mask.at<std::uint8_t>(y, x) != 0) continue;
    }
    keep.push_back(i);
  }
  auto f = std::make_shared<FrameFeatures>();
  const int n = static_cast<int>(keep.size());
  std::vector<cv::Point2f> raw(n);
  for (int k = 0; k < n; ++k) raw[k] = raw_keys[keep[k]].pt;
  const std::vector<cv::Point2f> und = sensor.camera().undistort(raw);
  f->keys.resize(n);
  f->descriptors.create(n, 32, CV_8U);
  f->depth.assign(n, -1.0f);
  f->u_right.assign(n, -1.0f);
  int with_depth = 0;
  for (int k = 0; k < n; ++k) {
    f->keys[k] = raw_keys[keep[k]];
    f->keys[k].pt = und[k];
    descriptors.row(keep[k]).copyTo(f->descriptors.row(k));
    // Depth is read at the distorted position: the depth image is registered to the raw colour image.
    const int x = cvRound(raw[k].x), y = cvRound(raw[k].y);
    if (x < 0 || y < 0 || x >= depth.cols || y >= depth.rows) continue;
    const float d = depth.at<float>(y, x);
    if (d > 0 && std::isfinite(d)) {
      f->depth[k] = d;
      f->u_right[k] = static_cast<float>(und[k].x - sensor.bf() / d);
      ++with_depth;
    }
  }
  f->grid = feature::KeypointGrid(cv::Rect2d(sensor.minU(), sensor.minV(), sensor.maxU() - sensor.minU(), sensor.maxV() - sensor.minV()), f->keys);
  if (stats) {
    stats->extracted = static_cast<int>(raw_keys.size());
    stats->removed_dynamic = static_cast<int>(raw_keys.size()) - n;
    stats->with_depth = with_depth;
  }
  return f;
}

cv::Mat makeThumbnail(const cv::Mat& gray) {
  cv::Mat small, blurred, out;
  cv::resize(gray, small, cv::Size(40, 30), 0, 0, cv::INTER_AREA);
  cv::GaussianBlur(small, blurred, cv::Size(5, 5), 1.5);
  blurred.convertTo(out, CV_32F);
  out -= cv::mean(out)[0];
  return out;
}

double thumbnailDistance(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || b.empty() || a.size() != b.size()) return std::numeric_limits<double>::max();
  return cv::norm(a, b, cv::NORM_L2SQR);
}

core::SE3 orthonormalized(const core::SE3& T) {
  core::SE3 out = core::SE3::Identity();
  out.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  out.translation() = T.translation();
  return out;
}

void Frame::resetMatches() {
  map_points.assign(size(), nullptr);
  outlier.assign(size(), false);
}

Eigen::Vector3d Frame::unproject(int i) const {
  const auto& kp = features->keys[i];
  const Eigen::Vector3d pc = sensor->camera().backProject(kp.pt.x, kp.pt.y, features->depth[i]);
  return T_cw.inverse() * pc;
}

Frame makeFrame(FrameId id, double timestamp, std::shared_ptr<const Sensor> sensor,
                std::shared_ptr<const FrameFeatures> features, cv::Mat thumbnail, cv::Mat dynamic_mask) {
  Frame f;
  f.id = id;
  f.timestamp = timestamp;
  f.sensor = std::move(sensor);
  f.features = std::move(features);
  f.thumbnail = std::move(thumbnail);
  f.dynamic_mask = std::move(dynamic_mask);
  f.resetMatches();
  return f;
}

}  // namespace amos::map
