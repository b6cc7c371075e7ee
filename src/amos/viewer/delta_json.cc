#include "amos/viewer/delta_json.h"

#include <cmath>

namespace amos::viewer {
namespace {

double mm(double v) { return std::round(v * 1000.0) / 1000.0; }
double rounded(double v, double unit) { return std::round(v / unit) * unit; }

nlohmann::json idsJson(const std::vector<std::uint64_t>& ids) { return nlohmann::json(ids); }

}  // namespace

nlohmann::json pointJson(const PointSample& p) {
  return {p.id, mm(p.position.x()), mm(p.position.y()), mm(p.position.z())};
}

nlohmann::json keyFrameJson(const KeyFrameSample& k) {
  const Eigen::Quaternionf& q = k.rotation;
  return {k.id, mm(k.position.x()), mm(k.position.y()), mm(k.position.z()), rounded(q.x(), 1e-4),
          rounded(q.y(), 1e-4), rounded(q.z(), 1e-4), rounded(q.w(), 1e-4)};
}

nlohmann::json trajectoryJson(const std::vector<TrajectoryPoint>& points) {
  nlohmann::json j = nlohmann::json::array();
  for (const TrajectoryPoint& p : points)
    j.push_back({rounded(p.timestamp, 1e-4), mm(p.position.x()), mm(p.position.y()), mm(p.position.z())});
  return j;
}

nlohmann::json updateJson(const LiveUpdate& u, std::uint64_t seq) {
  nlohmann::json j = {{"seq", seq}};
  auto list = [](const auto& items, auto encode) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& item : items) a.push_back(encode(item));
    return a;
  };
  if (!u.map.points.empty()) j["points"] = list(u.map.points, pointJson);
  if (!u.map.removed.empty()) j["removed"] = idsJson(u.map.removed);
  if (!u.map.culled.empty()) j["culled"] = list(u.map.culled, pointJson);
  if (!u.map.keyframes.empty()) j["keyframes"] = list(u.map.keyframes, keyFrameJson);
  if (!u.map.removed_keyframes.empty()) j["removed_keyframes"] = idsJson(u.map.removed_keyframes);
  if (!u.trajectory.empty() || u.trajectory_reset) j["trajectory"] = trajectoryJson(u.trajectory);
  if (u.trajectory_reset) j["trajectory_reset"] = true;
  if (u.ground_truth) j["ground_truth"] = trajectoryJson(*u.ground_truth);
  if (u.frame) j["frame"] = *u.frame;
  if (u.info) j["info"] = *u.info;
  if (u.summary) j["summary"] = *u.summary;
  if (u.frame_image) j["frame_image"] = true;
  return j;
}

nlohmann::json frameStatusJson(const run::FrameSnapshot& f, double fps) {
  const core::SE3 T_wc = f.T_cw.inverse();
  const Eigen::Quaterniond q(T_wc.rotation());
  const Eigen::Vector3d t = T_wc.translation();
  return {{"index", f.index},
          {"total", f.total},
          {"processed", f.processed},
          {"timestamp", f.timestamp},
          {"state", tracking::toString(f.state)},
          {"inliers", f.inliers},
          {"keyframe", f.new_keyframe},
          {"keypoints", f.keypoints.size()},
          {"removed", f.keypoints_removed},
          {"fps", rounded(fps, 0.1)},
          {"elapsed_s", rounded(f.elapsed_s, 0.01)},
          {"times_ms",
           {{"extract", rounded(f.extract_ms, 0.01)},
            {"build", rounded(f.build_ms, 0.01)},
            {"track", rounded(f.track_ms, 0.01)},
            {"frame", rounded(f.frame_ms, 0.01)}}},
          {"T_wc", {mm(t.x()), mm(t.y()), mm(t.z()), rounded(q.x(), 1e-4), rounded(q.y(), 1e-4),
                    rounded(q.z(), 1e-4), rounded(q.w(), 1e-4)}}};
}

}  // namespace amos::viewer
