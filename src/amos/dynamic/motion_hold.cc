#include "amos/dynamic/motion_hold.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "amos/core/error.h"
#include "amos/dynamic/frame_regions.h"

namespace amos::dynamic {

namespace {

// Whether the depth measured in the last frame is the one a static point predicts there: within three standard
// deviations of the difference of two measurements (the sensor's axial noise model, sqrt(2) sigma(z)), and at least
// 1 cm. One frame apart the sensor's bias is the same at both (it varies over the image, not from frame to frame),
// and a slow mover moves its surface by millimetres. The floor of a pushed box just behind where the box stood is
// some centimetres deeper than the box was: it does not inherit the box's score.
bool sameSurface(float measured, float predicted, const DepthEvidenceOptions& noise) {
  if (!(measured > 0.f)) return false;
  const double tolerance = std::max(0.01, 3.0 * std::sqrt(2.0) * noise.sigma(predicted));
  return std::abs(static_cast<double>(measured) - predicted) <= tolerance;
}

}  // namespace

std::vector<bool> stillSuperpixels(const std::vector<PointTrack>& tracks,
                                   const std::vector<std::optional<double>>& judged_error_px, const cv::Mat& labels,
                                   int count, double sigma_px) {
  core::require(labels.type() == CV_32S, "stillSuperpixels: labels must be CV_32S");
  core::require(judged_error_px.empty() || judged_error_px.size() == tracks.size(),
                "stillSuperpixels: one error per track (or none)");
  const auto n_sp = static_cast<std::size_t>(std::max(count, 0));
  std::vector<std::vector<double>> errors(n_sp);
  for (std::size_t i = 0; i < judged_error_px.size(); ++i) {
    if (!judged_error_px[i]) continue;
    const int label = labelAt(labels, tracks[i].current);
    if (label >= 0 && label < count) errors[static_cast<std::size_t>(label)].push_back(*judged_error_px[i]);
  }
  std::vector<bool> out(n_sp, false);
  for (std::size_t s = 0; s < n_sp; ++s) {
    std::vector<double>& e = errors[s];
    if (e.size() < 2) continue;
    const auto mid = e.begin() + static_cast<std::ptrdiff_t>(e.size() / 2);
    std::nth_element(e.begin(), mid, e.end());
    out[s] = *mid <= 2.0 * sigma_px;
  }
  return out;
}

MotionHold holdMotion(const MotionHoldInput& in, const core::PinholeCamera& camera, const DepthSampleGrid& grid,
                      const DepthEvidenceOptions& noise, int hold_frames, int min_frames) {
  core::require(min_frames >= 2 && hold_frames >= 1 && hold_frames + min_frames <= 256,
                "holdMotion: hold_frames >= 1, min_frames >= 2, their sum at most 256");
  core::require(in.evidence_mask && in.labels && in.depth, "holdMotion: evidence_mask, labels and depth are required");
  const cv::Mat& labels = *in.labels;
  const cv::Mat& depth = *in.depth;
  const cv::Mat& evidence = *in.evidence_mask;
  core::require(labels.type() == CV_32S && depth.type() == CV_32F && evidence.type() == CV_8UC1 &&
                    labels.size() == depth.size() && evidence.size() == depth.size(),
                "holdMotion: labels CV_32S, depth CV_32F and evidence_mask CV_8U of one size");
  const std::vector<cv::Point>& pixels = grid.pixels();
  core::require(!pixels.empty(), "holdMotion: empty sample grid");
  // The grid's samples, row by row: its columns are the samples of its first row; its step is their spacing.
  int cols = 0;
  while (cols < static_cast<int>(pixels.size()) && pixels[static_cast<std::size_t>(cols)].y == pixels[0].y) ++cols;
  const int rows = static_cast<int>(pixels.size()) / cols;
  const int step = cols > 1 ? pixels[1].x - pixels[0].x : std::max(depth.cols, 1);
  const int offset = pixels[0].x;
  const bool have_last = in.last_score && in.last_depth && !in.last_score->empty() && !in.last_depth->empty();
  if (have_last)
    core::require(in.last_score->type() == CV_8UC1 && in.last_score->rows == rows && in.last_score->cols == cols &&
                      in.last_depth->type() == CV_32F && in.last_depth->size() == depth.size(),
                  "holdMotion: last_score must be CV_8U of the sample grid's size, last_depth CV_32F of the frame's");
  const int count = std::max(in.count, 0);
  const auto n_sp = static_cast<std::size_t>(count);

  // Pass 1: each sample with a depth, lifted and moved into the last frame.
  std::vector<std::uint8_t> carried(pixels.size(), 0);
  if (have_last) {
    std::vector<int> lifted_index;
    std::vector<float> lifted_z;
    std::vector<cv::Point2f> projected;
    const core::SE3 T_last_cur = in.T_cw_last * in.T_cw.inverse();
    const Eigen::Matrix3d R = T_last_cur.linear();
    const Eigen::Vector3d t = T_last_cur.translation();
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      const float z = depth.at<float>(pixels[i]);
      if (!(z > 0.f)) continue;
      const cv::Point2d& xn = grid.normalised()[i];
      const Eigen::Vector3d X_last = R * Eigen::Vector3d(xn.x * z, xn.y * z, z) + t;
      if (X_last.z() <= 0.1) continue;
      const Eigen::Vector2d u = camera.project(X_last);
      lifted_index.push_back(static_cast<int>(i));
      lifted_z.push_back(static_cast<float>(X_last.z()));
      projected.emplace_back(static_cast<float>(u.x()), static_cast<float>(u.y()));
    }
    if (camera.intrinsics().hasDistortion()) projected = camera.distort(projected);
    const cv::Mat& last_score = *in.last_score;
    const cv::Mat& last_depth = *in.last_depth;
    for (std::size_t k = 0; k < projected.size(); ++k) {
      const int x = static_cast<int>(std::lround(projected[k].x)), y = static_cast<int>(std::lround(projected[k].y));
      if (x < 0 || y < 0 || x >= last_depth.cols || y >= last_depth.rows) continue;
      if (!sameSurface(last_depth.at<float>(y, x), lifted_z[k], noise)) continue;
      // The last frame's sample nearest to where the point was (at most half a step away).
      const int c = std::clamp(static_cast<int>(std::lround(static_cast<double>(x - offset) / step)), 0, cols - 1);
      const int r = std::clamp(static_cast<int>(std::lround(static_cast<double>(y - offset) / step)), 0, rows - 1);
      carried[static_cast<std::size_t>(lifted_index[k])] = last_score.at<std::uint8_t>(r, c);
    }
  }

  // Pass 2: each sample's score, and per superpixel its samples, those found moving and those the hold keeps.
  MotionHold out;
  out.score = cv::Mat(rows, cols, CV_8U, cv::Scalar(0));
  std::vector<int> samples(n_sp, 0), found(n_sp, 0), kept(n_sp, 0);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const cv::Point p = pixels[i];
    const bool moving = evidence.at<std::uint8_t>(p) != 0;
    const int before = carried[i];
    int now = moving ? std::min(before + 1, hold_frames + min_frames - 1) : std::max(before - 1, 0);
    const int label = labels.at<int>(p);
    const bool labelled = label >= 0 && label < count;
    const auto s = static_cast<std::size_t>(labelled ? label : 0);
    if (labelled && !moving && in.seen_static && s < in.seen_static->size() && (*in.seen_static)[s]) now = 0;
    out.score.at<std::uint8_t>(static_cast<int>(i) / cols, static_cast<int>(i) % cols) = static_cast<std::uint8_t>(now);
    if (!labelled) continue;
    ++samples[s];
    if (moving) ++found[s];
    if (!moving && now > 0 && now >= min_frames - 1) ++kept[s];
  }
  out.held.assign(n_sp, false);
  for (std::size_t s = 0; s < n_sp; ++s)
    if (2 * found[s] <= samples[s] && 2 * kept[s] > samples[s]) {
      out.held[s] = true;
      ++out.held_superpixels;
    }
  return out;
}

}  // namespace amos::dynamic
