#pragma once
// Which surface points later depth readings see through (issue 55). A TSDF only updates the voxels near each new
// surface, so a surface fused once (a person the dynamic mask missed for a few frames) stays after it has gone;
// the frames that look through where it stood are the evidence that it is free space now.
//
// Each point is projected into each frame (pinhole, undistorted image; T_cw the frame's pose). With z the point's
// depth and r the reading at its pixel, the band is
//     band = truncation + sigmas * sigma(max(z, r)),   sigma(z) = DenseOptions::depthNoise(z) (the sensor's noise)
// and the frame votes
//   support       |r - z| <= band: the surface is where the point is;
//   see-through   every valid reading of the 3x3 pixels around the point's pixel lies beyond z + band: the ray went
//                 on through the point. All nine, not only the nearest: at a grazing angle a pixel's ray meets a
//                 surface far behind a point that lies a sub-pixel off it, but a neighbour's ray meets it in the band;
//   nothing       no reading (invalid, left out as dynamic or as a depth edge), the point outside the image or the
//                 depth range, or the reading in front of the point (it is hidden: no evidence either way).
// The truncation is in the band because the fused surface is a weighted mean of readings over the truncation band
// and the poses carry their own errors; sigma grows with range as the sensor's noise does (a constant fitted to one
// sequence would carve far walls or spare near ghosts). A point is seen through when the see-through votes reach
// `min_votes` and outnumber the support votes, or when its last `recent_votes` votes all saw through it (0 = not
// this rule): one noisy frame does not decide, a surface seen many times before it left needs as many frames
// that look through it, unless every frame since it was last seen looked through it: a person who stood for
// seconds and then walked away.
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "amos/core/camera.h"
#include "amos/core/pose.h"

namespace amos::dense {

struct SeeThroughOptions {
  double truncation = 0.06;  // Dense.truncation (m)
  double sigmas = 3.0;       // Dense.carveSigmas: the band holds this many sigma of the depth noise
  double min_depth = 0.3;    // points nearer or farther than these (m) are not voted on in a frame
  double max_depth = 4.0;
  int min_votes = 3;         // Dense.carveMinVotes: see-through votes a point needs at least
  int recent_votes = 0;      // Dense.carveRecentVotes: ... or this many in a row since its last support (0 = off)

  double band(double z) const;  // truncation + sigmas * sigma(z)
};

struct SeeThroughCounts {
  std::uint32_t support = 0, through = 0;
  std::uint32_t through_since_support = 0;  // see-through votes since the last support vote
};

class SeeThroughVote {
 public:
  SeeThroughVote(std::vector<Eigen::Vector3d> points, const SeeThroughOptions& options);

  // depth: CV_32F metres (0 = no reading) of the undistorted `camera`'s size; T_cw: world to camera.
  void addFrame(const cv::Mat& depth, const core::CameraIntrinsics& camera, const core::SE3& T_cw);

  std::size_t size() const { return points_.size(); }
  const Eigen::Vector3d& point(std::size_t i) const { return points_[i]; }
  const SeeThroughCounts& counts(std::size_t i) const { return counts_[i]; }
  bool seenThrough(std::size_t i) const;
  std::vector<std::size_t> seenThroughIndices() const;
  std::size_t seenThroughCount() const;
  std::size_t frames() const { return frames_; }

 private:
  std::vector<Eigen::Vector3d> points_;
  std::vector<SeeThroughCounts> counts_;
  SeeThroughOptions options_;
  std::size_t frames_ = 0;
};

}  // namespace amos::dense
