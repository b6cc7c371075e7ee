#include "amos/viewer/report_html.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"
#include "amos/viewer/base64.h"
#include "amos/viewer/delta_json.h"
#include "amos/viewer/ground_truth_overlay.h"
#include "amos/viewer/occupancy_grid.h"
#include "amos/viewer/web_assets.h"

namespace amos::viewer {
namespace {

constexpr char kDataMarker[] = "__AMOS_REPORT_DATA__";

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

nlohmann::json positions(const std::vector<double>& stamps, const std::vector<Eigen::Vector3d>& p) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i = 0; i < p.size() && i < stamps.size(); ++i) out.push_back({stamps[i], p[i].x(), p[i].y(), p[i].z()});
  return out;
}

}  // namespace

// Keys: run{...stats summary}, settings{file, text, options}, frames{index, t, state, extract_ms, build_ms,
// track_ms, frame_ms, keypoints, removed, removed_fraction}, trajectory [[t,x,y,z]] (aligned to the ground truth
// when there is one), ground_truth [[t,x,y,z]] (the associated poses), ate{t, error_m}, rpe{t, trans_m, rot_deg},
// steps{t, est_m, gt_m, error_m} (frame-to-frame steps and their RPE, eval/jitter.h), evaluation (eval::toJson),
// overlays [{index, t, jpeg (base64)}], stats (stats.json), view{ground_truth [[t,x,y,z]] in the map's frame,
// culled [[id,x,y,z]]: the map points removed as dynamic}.
nlohmann::json reportData(const ReportRecorder& recorder, const ReportInputs& inputs) {
  nlohmann::json d;
  d["stats"] = inputs.stats;
  d["settings"] = {{"file", inputs.settings_file}, {"text", inputs.settings_text}, {"options", inputs.run_options}};
  nlohmann::json frames = {{"index", nlohmann::json::array()}, {"t", nlohmann::json::array()},
                           {"state", nlohmann::json::array()}, {"extract_ms", nlohmann::json::array()},
                           {"build_ms", nlohmann::json::array()}, {"track_ms", nlohmann::json::array()},
                           {"frame_ms", nlohmann::json::array()}, {"keypoints", nlohmann::json::array()},
                           {"removed", nlohmann::json::array()}, {"removed_fraction", nlohmann::json::array()}};
  for (const ReportFrame& f : recorder.frames()) {
    frames["index"].push_back(f.index);
    frames["t"].push_back(f.timestamp);
    frames["state"].push_back(f.state);
    frames["extract_ms"].push_back(f.extract_ms);
    frames["build_ms"].push_back(f.build_ms);
    frames["track_ms"].push_back(f.track_ms);
    frames["frame_ms"].push_back(f.frame_ms);
    frames["keypoints"].push_back(f.keypoints);
    frames["removed"].push_back(f.removed);
    frames["removed_fraction"].push_back(f.keypoints > 0 ? static_cast<double>(f.removed) / f.keypoints : 0.0);
  }
  d["frames"] = std::move(frames);
  if (const auto& e = recorder.evaluation()) {
    d["evaluation"] = eval::toJson(*e);
    d["trajectory"] = positions(e->ate.est_stamps, e->ate.est_positions_aligned);
    d["ground_truth"] = positions(e->ate.gt_stamps, e->ate.gt_positions);
    d["ate"] = {{"t", e->ate.est_stamps}, {"error_m", e->ate.errors_m}};
    nlohmann::json rpe = {{"t", nlohmann::json::array()}, {"trans_m", nlohmann::json::array()},
                          {"rot_deg", nlohmann::json::array()}};
    for (const eval::RpePair& p : e->rpe.pairs) {
      rpe["t"].push_back(p.est_stamp_0);
      rpe["trans_m"].push_back(number(p.trans_error_m));
      rpe["rot_deg"].push_back(number(p.rot_error_rad * 180.0 / M_PI));
    }
    d["rpe"] = std::move(rpe);
    nlohmann::json steps = {{"t", nlohmann::json::array()}, {"est_m", nlohmann::json::array()},
                            {"gt_m", nlohmann::json::array()}, {"error_m", nlohmann::json::array()}};
    for (const eval::JitterStep& s : e->jitter.steps) {
      steps["t"].push_back(s.est_stamp_1);
      steps["est_m"].push_back(number(s.est_step_m));
      steps["gt_m"].push_back(number(s.gt_step_m));
      steps["error_m"].push_back(number(s.trans_error_m));
    }
    d["steps"] = std::move(steps);
  } else {
    nlohmann::json t = nlohmann::json::array();
    for (const io::StampedPose& p : recorder.trajectory()) {
      const Eigen::Vector3d c = p.T_wc.translation();
      t.push_back({p.timestamp, c.x(), c.y(), c.z()});
    }
    d["trajectory"] = std::move(t);
    d["ground_truth"] = nlohmann::json::array();
  }
  nlohmann::json overlays = nlohmann::json::array();
  for (const ReportOverlay& o : recorder.overlays())
    overlays.push_back({{"index", o.index}, {"t", o.timestamp}, {"jpeg", base64Encode(o.jpeg)}});
  d["overlays"] = std::move(overlays);
  // What `amos-slam view` shows of the run beside its other files (run_folder.h): the ground truth in the map's
  // frame, as the live page drew it at the end, and the map points removed as dynamic.
  nlohmann::json view = nlohmann::json::object();
  if (const auto& e = recorder.evaluation(); e && !recorder.groundTruth().empty())
    view["ground_truth"] = trajectoryJson(groundTruthInMapFrame(recorder.groundTruth(), e->alignment));
  if (!recorder.culledPoints().empty()) {
    nlohmann::json culled = nlohmann::json::array();
    for (const PointSample& p : recorder.culledPoints()) culled.push_back(pointJson(p));
    view["culled"] = std::move(culled);
  }
  d["view"] = std::move(view);
  return d;
}

void addDenseProducts(const std::filesystem::path& dir, nlohmann::json& data) {
  nlohmann::json files = nlohmann::json::array();
  for (const char* name : {"mesh.ply", "cloud.ply", "removed_points.ply", "occupancy.pgm", "occupancy.yaml"}) {
    std::error_code error;
    const auto bytes = std::filesystem::file_size(dir / name, error);
    if (!error) files.push_back({{"name", name}, {"bytes", bytes}});
  }
  data["dense_files"] = std::move(files);
  if (!std::filesystem::exists(dir / "occupancy.yaml")) return;
  try {
    data["occupancy"] = occupancyReportJson(readOccupancyGrid(dir / "occupancy.yaml"));
  } catch (const core::Error& e) {
    spdlog::warn("report.html: no occupancy grid: {}", e.what());
    data["occupancy"] = {{"error", e.what()}};
  }
}

std::string reportHtml(const nlohmann::json& data) {
  std::string json = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  // "<\/" is the same string in JSON and cannot close the script element.
  for (std::size_t at = json.find("</"); at != std::string::npos; at = json.find("</", at + 3)) json.insert(at + 1, "\\");
  std::string page(webAssetText("report_template.html"));
  const std::size_t at = page.find(kDataMarker);
  core::require(at != std::string::npos, "viewer: report_template.html has no data marker");
  page.replace(at, sizeof(kDataMarker) - 1, json);
  return page;
}

void writeReportHtml(const std::filesystem::path& dir, const ReportRecorder& recorder, const ReportInputs& inputs) {
  nlohmann::json data = reportData(recorder, inputs);
  addDenseProducts(dir, data);
  io::writeFileAtomically((dir / "report.html").string(), reportHtml(data));
}

}  // namespace amos::viewer
