#include "amos/eval/see_through_share.h"

#include <fmt/format.h>

#include "amos/core/error.h"
#include "amos/dense/free_space_carving.h"
#include "amos/eval/mesh_eval.h"
#include "amos/io/dataset.h"
#include "amos/io/image_codecs.h"
#include "amos/io/image_read_flags.h"
#include "amos/io/poses_by_stamp.h"
#include "amos/io/trajectory.h"

namespace amos::eval {

namespace {

// The carving's band and votes, without its recency rule: the measure counts the vertices seen through more
// often than seen.
dense::SeeThroughOptions measureOptions(const dense::DenseOptions& dense) {
  dense::SeeThroughOptions out = dense::seeThroughOptionsOf(dense);
  out.recent_votes = 0;
  return out;
}

}  // namespace

SeeThroughScorer::SeeThroughScorer(std::vector<Eigen::Vector3d> vertices, const core::CameraIntrinsics& camera,
                                   const dense::DenseOptions& dense)
    : preparer_(camera, dense),
      vote_(std::move(vertices), measureOptions(dense)),
      no_colour_(cv::Mat::zeros(camera.height, camera.width, CV_8UC3)) {}

void SeeThroughScorer::addFrame(const cv::Mat& depth, const core::SE3& T_wc) {
  const dense::PreparedFrame frame = preparer_.prepare({depth, no_colour_, cv::Mat()});
  vote_.addFrame(frame.depth, preparer_.intrinsics(), T_wc.inverse());
}

SeeThroughScore SeeThroughScorer::score() const {
  SeeThroughScore s;
  s.vertices = vote_.size();
  s.frames = vote_.frames();
  for (std::size_t i = 0; i < vote_.size(); ++i) {
    const dense::SeeThroughCounts& c = vote_.counts(i);
    s.voted += c.support + c.through > 0 ? 1 : 0;
    if (vote_.seenThrough(i)) s.points.push_back(vote_.point(i));
  }
  s.seen_through = s.points.size();
  s.share = s.vertices == 0 ? 0.0 : static_cast<double>(s.seen_through) / static_cast<double>(s.vertices);
  return s;
}

namespace {

cv::Mat depthMetres(const std::string& file, double depth_factor) {
  std::string problem;
  const cv::Mat raw = io::readImage(file, io::kReadUnchanged, &problem);
  core::require(!raw.empty(), fmt::format("{}: cannot read the depth image: {}", file, problem));
  core::require(raw.type() == CV_16U, fmt::format("{}: not a 16-bit depth image", file));
  cv::Mat metres;
  raw.convertTo(metres, CV_32F, 1.0 / depth_factor);
  return metres;
}

}  // namespace

SeeThroughScore evaluateSeeThrough(const SeeThroughRequest& request) {
  const io::PosesByStamp poses =
      io::posesByStamp(io::readTumTrajectoryWithPoses(request.trajectory, "trajectory"));
  SeeThroughScorer scorer(readMeshVertices(request.mesh), request.camera, request.dense);
  for (const io::AssociatedFrame& frame : io::indexSequence(request.sequence).frames) {
    // Stamps read back from trajectory.txt: equal to the frame's up to the file's rounding.
    const core::SE3* T_wc = io::poseNear(poses, frame.t_rgb, 1e-4);
    if (T_wc != nullptr) scorer.addFrame(depthMetres(frame.depth_file, request.depth_factor), *T_wc);
  }
  SeeThroughScore score = scorer.score();
  core::require(score.frames > 0, fmt::format("{}: no frame of {} has a pose in it", request.trajectory,
                                              request.sequence));
  score.band_at_2m = dense::seeThroughOptionsOf(request.dense).band(2.0);
  return score;
}

nlohmann::json toJson(const SeeThroughScore& s) {
  return {{"vertices", s.vertices},         {"voted", s.voted},   {"seen_through", s.seen_through},
          {"seen_through_share", s.share},  {"frames", s.frames}, {"band_at_2m_m", s.band_at_2m}};
}

}  // namespace amos::eval
