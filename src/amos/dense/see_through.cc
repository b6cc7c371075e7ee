#include "amos/dense/see_through.h"

#include <algorithm>
#include <cmath>

#include "amos/core/error.h"
#include "amos/dense/dense_options.h"

namespace amos::dense {

namespace {

enum class Vote { kNone, kSupport, kThrough };

// The vote of the readings around pixel (u, v) on a point at depth z (see_through.h).
Vote voteAt(const cv::Mat& depth, int u, int v, double z, const SeeThroughOptions& options) {
  const float centre = depth.at<float>(v, u);
  if (centre <= 0) return Vote::kNone;
  const double r = centre;
  if (std::abs(r - z) <= options.band(std::max(z, r))) return Vote::kSupport;
  if (r < z) return Vote::kNone;  // in front: the point is hidden
  for (int dv = -1; dv <= 1; ++dv) {
    for (int du = -1; du <= 1; ++du) {
      const int uu = u + du, vv = v + dv;
      if (uu < 0 || vv < 0 || uu >= depth.cols || vv >= depth.rows) continue;
      const float reading = depth.at<float>(vv, uu);
      if (reading <= 0) continue;
      if (reading <= z + options.band(reading)) return Vote::kNone;  // a neighbour's ray meets the surface
    }
  }
  return Vote::kThrough;
}

}  // namespace

double SeeThroughOptions::band(double z) const { return truncation + sigmas * DenseOptions::depthNoise(z); }

SeeThroughVote::SeeThroughVote(std::vector<Eigen::Vector3d> points, const SeeThroughOptions& options)
    : points_(std::move(points)), counts_(points_.size()), options_(options) {
  core::require(options.truncation > 0 && options.sigmas >= 0 && options.min_votes >= 1 && options.recent_votes >= 0 &&
                    options.max_depth > options.min_depth,
                "SeeThroughVote: truncation > 0, sigmas >= 0, min_votes >= 1 and max_depth > min_depth expected");
}

void SeeThroughVote::addFrame(const cv::Mat& depth, const core::CameraIntrinsics& camera, const core::SE3& T_cw) {
  core::require(depth.type() == CV_32F && depth.cols == camera.width && depth.rows == camera.height,
                "SeeThroughVote::addFrame: depth CV_32F of the camera's size expected");
  ++frames_;
  const Eigen::Matrix3d R = T_cw.linear();
  const Eigen::Vector3d t = T_cw.translation();
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Eigen::Vector3d p = R * points_[i] + t;
    const double z = p.z();
    if (z < options_.min_depth || z > options_.max_depth) continue;
    const int u = static_cast<int>(std::lround(camera.fx * p.x() / z + camera.cx));
    const int v = static_cast<int>(std::lround(camera.fy * p.y() / z + camera.cy));
    if (u < 0 || v < 0 || u >= depth.cols || v >= depth.rows) continue;
    switch (voteAt(depth, u, v, z, options_)) {
      case Vote::kSupport:
        ++counts_[i].support;
        counts_[i].through_since_support = 0;
        break;
      case Vote::kThrough:
        ++counts_[i].through;
        ++counts_[i].through_since_support;
        break;
      case Vote::kNone: break;
    }
  }
}

bool SeeThroughVote::seenThrough(std::size_t i) const {
  const SeeThroughCounts& c = counts_[i];
  if (c.through < static_cast<std::uint32_t>(options_.min_votes)) return false;
  const bool recent = options_.recent_votes > 0 &&
                      c.through_since_support >= static_cast<std::uint32_t>(options_.recent_votes);
  return c.through > c.support || recent;
}

std::vector<std::size_t> SeeThroughVote::seenThroughIndices() const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (seenThrough(i)) out.push_back(i);
  }
  return out;
}

std::size_t SeeThroughVote::seenThroughCount() const { return seenThroughIndices().size(); }

}  // namespace amos::dense
