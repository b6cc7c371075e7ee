#pragma once
// A ghost measure without ground truth (issue 55): the share of a mesh's vertices that the run's own frames see
// through. Each frame's depth (undistorted, the depth range and the depth edges left out as the fusion does, no
// dynamic mask: the raw scene) is placed with the run's trajectory, every vertex projected into it and voted on
// as dense/see_through.h says: support when the reading lies within truncation + carveSigmas x sigma(z) of the
// vertex, see-through when every reading around its pixel lies beyond that band. A vertex is seen through when
// the see-through votes reach carveMinVotes and outnumber the support (the carving's recency rule is left out):
// a surface that was there once and is free
// space now (a person fused where the mask missed and who walked on). A static surface is seen, never seen
// through, whatever moved in front of it (a reading in front of a vertex hides it: no vote), so any real sequence
// can be scored; on synthetic truth it agrees with the swept-volume ghosts of mesh_eval.h (see_through_share_test).
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dense/dense_options.h"
#include "amos/dense/frame_preparation.h"
#include "amos/dense/see_through.h"

namespace amos::eval {

struct SeeThroughScore {
  std::size_t vertices = 0;
  std::size_t voted = 0;         // vertices with at least one vote
  std::size_t seen_through = 0;  // seen through (the vote above)
  std::size_t frames = 0;
  double share = 0;              // seen_through / vertices
  double band_at_2m = 0;         // the band (m) at 2 m, for the record
  std::vector<Eigen::Vector3d> points;  // the vertices seen through (mesh frame), to look at; not in toJson
};

class SeeThroughScorer {
 public:
  // camera: the sequence's lens (with its distortion); dense: the run's Dense.* settings (band, range, edges, scale).
  SeeThroughScorer(std::vector<Eigen::Vector3d> vertices, const core::CameraIntrinsics& camera,
                   const dense::DenseOptions& dense);
  // depth: CV_32F metres (0 = none) as the sensor gave it; T_wc: the run's pose of the frame.
  void addFrame(const cv::Mat& depth, const core::SE3& T_wc);
  SeeThroughScore score() const;

 private:
  dense::FramePreparer preparer_;
  dense::SeeThroughVote vote_;
  cv::Mat no_colour_;
};

struct SeeThroughRequest {
  std::string mesh;        // the run's mesh.ply (world frame of its trajectory)
  std::string sequence;    // the sequence folder (TUM / Bonn layout) the run read
  std::string trajectory;  // the run's trajectory.txt
  core::CameraIntrinsics camera;
  double depth_factor = 5000.0;  // DepthMapFactor
  dense::DenseOptions dense;
};

// Every frame of the sequence whose colour time stamp the trajectory holds. Throws core::Error naming the file that
// cannot be read, or when no frame has a pose.
SeeThroughScore evaluateSeeThrough(const SeeThroughRequest& request);

nlohmann::json toJson(const SeeThroughScore& score);

}  // namespace amos::eval
