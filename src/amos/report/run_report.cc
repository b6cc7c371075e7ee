#include "amos/report/run_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <filesystem>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"
#include "amos/io/trajectory.h"

namespace amos::report {

const char* toString(RunEnd::Status status) {
  switch (status) {
    case RunEnd::Status::kComplete: return "complete";
    case RunEnd::Status::kInterrupted: return "interrupted";
    case RunEnd::Status::kFailed: return "failed";
  }
  return "?";
}

const char* toString(OptionalStage::Status status) {
  switch (status) {
    case OptionalStage::Status::kDone: return "done";
    case OptionalStage::Status::kFailed: return "failed";
    case OptionalStage::Status::kInterrupted: return "interrupted";
    case OptionalStage::Status::kSkipped: return "skipped";
  }
  return "?";
}

nlohmann::json toJson(const SourceReport& source) {
  nlohmann::json j = {{"kind", source.kind},
                      {"delivered", source.delivered},
                      {"processed", source.processed},
                      {"dropped", source.dropped},
                      {"segmentation_late", source.segmentation_late}};
  if (!source.latency_ms.empty()) {
    j["latency_ms"] = {{"median", core::percentile(source.latency_ms, 0.5)},
                       {"p95", core::percentile(source.latency_ms, 0.95)},
                       {"max", *std::max_element(source.latency_ms.begin(), source.latency_ms.end())}};
  }
  if (!source.recorded_to.empty()) j["recorded_to"] = source.recorded_to;
  return j;
}

nlohmann::json toJson(const io::AssociationStats& association) {
  return {{"file", association.file},
          {"rows", association.rows},
          {"rows_beyond_window", association.rows_beyond_window},
          {"duplicate_rows", association.duplicate_rows},
          {"window_s", association.window_s}};
}

nlohmann::json statsJson(const system::SlamStats& s, const core::StageTimes& times, const RunInfo& info) {
  nlohmann::json j;
  j["sequence"] = info.sequence;
  j["config"] = info.config;
  j["mode"] = info.mode;
  j["deterministic"] = info.deterministic;
  j["end"] = {{"status", toString(info.end.status)}, {"reason", info.end.reason}};
  j["frames"] = s.frames;
  j["tracked"] = s.tracked;
  j["lost"] = s.lost;
  j["not_initialized"] = s.not_initialized;
  j["relocalised"] = s.relocalized;
  j["keyframes"] = s.keyframes;
  j["keyframes_created"] = s.keyframes_created;
  j["map_points"] = s.map_points;
  j["mapping"] = {{"keyframes_processed", s.mapping.keyframes_processed},
                  {"keyframes_culled", s.mapping.keyframes_culled},
                  {"points_triangulated", s.mapping.points_triangulated},
                  {"points_culled", s.mapping.points_culled},
                  {"points_fused", s.mapping.points_fused},
                  {"local_ba_runs", s.mapping.ba_runs},
                  {"local_ba_aborted", s.mapping.ba_aborted},
                  {"dynamic_points_culled", s.mapping.dynamic_points_culled},
                  {"loops_closed", s.loops_closed}};
  nlohmann::json stages = nlohmann::json::object();
  auto addStages = [&stages](const core::StageTimes& source) {
    for (const auto& [name, sum] : source.summary()) {
      stages[name] = {{"count", sum.count}, {"median_ms", sum.median_ms}, {"p95_ms", sum.p95_ms},
                      {"mean_ms", sum.mean_ms}, {"max_ms", sum.max_ms}};
    }
  };
  addStages(times);
  if (info.front_end_times) addStages(*info.front_end_times);
  j["stages"] = stages;
  if (!info.removed_fractions.empty()) {
    j["removed_keypoint_fraction"] = {{"median", core::percentile(info.removed_fractions, 0.5)},
                                      {"p95", core::percentile(info.removed_fractions, 0.95)},
                                      {"per_frame", info.removed_fractions}};
  }
  for (const auto& [name, section] : info.sections.items()) j[name] = section;
  if (!info.optional_stages.empty()) {
    nlohmann::json stages_json = nlohmann::json::object();
    for (const auto& [name, stage] : info.optional_stages)
      stages_json[name] = {{"status", toString(stage.status)}, {"reason", stage.reason}};
    j["optional_stages"] = stages_json;
  }
  j["wall_time_s"] = info.wall_time_s;
  j["fps"] = info.wall_time_s > 0 ? static_cast<double>(s.frames) / info.wall_time_s : 0.0;
  if (info.mask_outputs_s > 0) j["mask_outputs_s"] = info.mask_outputs_s;
  if (info.evaluation) j["evaluation"] = eval::toJson(*info.evaluation);
  if (info.mask_accuracy) {
    j["mask_accuracy"] = eval::toJson(*info.mask_accuracy);
    if (!info.instance_accuracy.empty()) j["mask_accuracy"]["instances"] = eval::toJson(info.instance_accuracy);
  }
  if (info.source) j["source"] = toJson(*info.source);
  if (info.association) j["association"] = toJson(*info.association);
  nlohmann::json skipped = nlohmann::json::object();
  for (const io::FrameProblem problem : io::kFrameProblems)
    skipped[io::frameProblemName(problem)] = info.skipped_frames.count(problem);
  j["skipped_frames"] = skipped;
  j["depth_dropouts"] = {{"frames", info.depth_dropouts.frames},
                         {"tracked", info.depth_dropouts.tracked},
                         {"lost", info.depth_dropouts.lost}};
  return j;
}

void writeMapPly(const std::string& path, const std::vector<Eigen::Vector3d>& points) {
  std::string text = "ply\nformat ascii 1.0\ncomment Amos-SLAM map points (world frame, metres)\n";
  text += "element vertex " + std::to_string(points.size()) +
          "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (const auto& p : points) fmt::format_to(std::back_inserter(text), "{:.6f} {:.6f} {:.6f}\n", p.x(), p.y(), p.z());
  io::writeFileAtomically(path, text);
}

void writeRunOutputs(const std::string& dir, const system::SlamSystem& slam, const RunInfo& info) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  core::require(!ec, "cannot create output folder " + dir + ": " + ec.message());
  const std::filesystem::path d(dir);
  io::writeTumTrajectory((d / "trajectory.txt").string(), slam.trajectory());
  io::writeTumTrajectory((d / "keyframes.txt").string(), slam.keyframeTrajectory());
  writeMapPly((d / "map.ply").string(), slam.mapPointPositions());
  writeStatsJson(dir, slam, info);
}

void writeStatsJson(const std::string& dir, const system::SlamSystem& slam, const RunInfo& info) {
  io::writeFileAtomically((std::filesystem::path(dir) / "stats.json").string(),
                          statsJson(slam.stats(), slam.times(), info).dump(2) + "\n");
}

}  // namespace amos::report
