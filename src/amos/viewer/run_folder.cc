#include "amos/viewer/run_folder.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "amos/core/error.h"
#include "amos/io/trajectory.h"
#include "amos/viewer/ply_file.h"
#include "amos/core/whole_file.h"

namespace amos::viewer {

namespace fs = std::filesystem;

std::optional<fs::path> runFilePath(const fs::path& root, const std::string& request) {
  if (request.empty() || request.front() == '/' || request.find('\\') != std::string::npos ||
      request.find('\0') != std::string::npos)
    return std::nullopt;
  const fs::path relative(request);
  if (relative.is_absolute() || relative.has_root_name()) return std::nullopt;
  for (const fs::path& part : relative)
    if (part == ".." || part == "." || part.empty()) return std::nullopt;
  std::error_code error;
  const fs::path base = fs::canonical(root, error);
  if (error) return std::nullopt;
  const fs::path file = fs::canonical(base / relative, error);
  if (error || !fs::is_regular_file(file, error)) return std::nullopt;
  // Inside the root also after symbolic links were followed.
  const auto [end, unused] = std::mismatch(base.begin(), base.end(), file.begin(), file.end());
  if (end != base.end()) return std::nullopt;
  return file;
}

namespace {

std::vector<TrajectoryPoint> centres(const std::vector<io::StampedPose>& poses) {
  std::vector<TrajectoryPoint> out;
  for (const io::StampedPose& p : poses) out.push_back({p.timestamp, p.T_wc.translation().cast<float>()});
  return out;
}

std::vector<PointSample> mapPoints(const fs::path& path) {
  const ColouredGeometry g = readPly(path);
  std::vector<PointSample> points(g.vertexCount());
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i].id = i;
    points[i].position = Eigen::Vector3f(g.xyz[3 * i], g.xyz[3 * i + 1], g.xyz[3 * i + 2]);
  }
  return points;
}

// The data block of the run's report.html (report_html.h), null when there is none or it cannot be read.
nlohmann::json reportDataOf(const fs::path& report) {
  const std::string html = core::readWholeFile(report).value_or(std::string());
  const std::string open = "<script id=\"amos-report-data\" type=\"application/json\">";
  const std::size_t begin = html.find(open);
  if (begin == std::string::npos) return nullptr;
  const std::size_t end = html.find("</script>", begin);
  if (end == std::string::npos) return nullptr;
  return nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()), nullptr, false);
}

std::vector<TrajectoryPoint> trajectoryOf(const nlohmann::json& rows) {
  std::vector<TrajectoryPoint> out;
  for (const nlohmann::json& r : rows)
    if (r.is_array() && r.size() == 4 && r[0].is_number() && r[1].is_number() && r[2].is_number() && r[3].is_number())
      out.push_back({r[0].get<double>(), Eigen::Vector3f(r[1].get<float>(), r[2].get<float>(), r[3].get<float>())});
  return out;
}

// Rows [id, x, y, z] (delta_json.h); malformed rows are skipped.
std::vector<PointSample> pointsOf(const nlohmann::json& rows) {
  std::vector<PointSample> out;
  for (const nlohmann::json& r : rows) {
    if (!r.is_array() || r.size() != 4 || !r[0].is_number_unsigned()) continue;
    if (!r[1].is_number() || !r[2].is_number() || !r[3].is_number()) continue;
    PointSample p;
    p.id = r[0].get<std::uint64_t>();
    p.position = Eigen::Vector3f(r[1].get<float>(), r[2].get<float>(), r[3].get<float>());
    out.push_back(p);
  }
  return out;
}

// The mask overlays: the files of --save-masks, else the strip report.html carries (as data: URLs).
nlohmann::json overlaysOf(const fs::path& dir, const nlohmann::json& report) {
  std::vector<std::string> names;
  if (fs::is_directory(dir / "overlays"))
    for (const auto& e : fs::directory_iterator(dir / "overlays"))
      if (e.is_regular_file() && e.path().extension() == ".png") names.push_back("overlays/" + e.path().filename().string());
  std::sort(names.begin(), names.end());
  nlohmann::json overlays = names;
  if (!names.empty() || !report.is_object() || !report.contains("overlays")) return overlays;
  for (const nlohmann::json& o : report["overlays"])
    if (o.is_object() && o.contains("jpeg") && o["jpeg"].is_string())
      overlays.push_back({{"src", "data:image/jpeg;base64," + o["jpeg"].get<std::string>()},
                          {"title", "frame " + o.value("index", nlohmann::json(0)).dump()}});
  return overlays;
}

// The dense products of `run --dense`, each a layer of the page; one that cannot be read is left out (a warning).
void loadDenseLayers(const fs::path& dir, LiveState& state) {
  for (const auto& [file, layer] : {std::pair{"mesh.ply", "mesh"}, {"cloud.ply", "cloud"}, {"removed_points.ply", "removed"}}) {
    if (!fs::exists(dir / file)) continue;
    try {
      state.setDenseLayer(layer, readPly(dir / file));
    } catch (const core::Error& e) {
      spdlog::warn("view: {} left out: {}", file, e.what());
    }
  }
}

}  // namespace

void loadRunFolder(const fs::path& dir, LiveState& state) {
  const bool has_trajectory = fs::exists(dir / "trajectory.txt"), has_stats = fs::exists(dir / "stats.json");
  core::require(has_trajectory || has_stats,
                fmt::format("view: {} holds no run (no trajectory.txt or stats.json)", dir.string()));
  LiveUpdate u;
  nlohmann::json info = {{"sequence", dir.string()}, {"live", false}};
  if (has_stats) {
    try {
      const nlohmann::json stats = nlohmann::json::parse(core::readWholeFile(dir / "stats.json").value_or(std::string()));
      u.summary = stats;
      for (const char* key : {"sequence", "mode", "config"})
        if (stats.contains(key)) info[key] = stats[key];
      if (stats.contains("frames")) info["frames"] = stats["frames"];
    } catch (const nlohmann::json::exception& e) {
      throw core::Error(fmt::format("view: {}: not valid JSON: {}", (dir / "stats.json").string(), e.what()));
    }
  }
  if (has_trajectory) {
    u.trajectory = centres(io::readTumTrajectory((dir / "trajectory.txt").string()));
    u.trajectory_reset = true;
  }
  if (fs::exists(dir / "keyframes.txt")) {
    const std::vector<io::StampedPose> keyframes = io::readTumTrajectory((dir / "keyframes.txt").string());
    for (std::size_t i = 0; i < keyframes.size(); ++i) {
      KeyFrameSample k;
      k.id = i;
      k.position = keyframes[i].T_wc.translation().cast<float>();
      k.rotation = Eigen::Quaternionf(keyframes[i].T_wc.rotation().cast<float>());
      u.map.keyframes.push_back(k);
    }
  }
  if (fs::exists(dir / "map.ply")) u.map.points = mapPoints(dir / "map.ply");
  const nlohmann::json report = fs::exists(dir / "report.html") ? reportDataOf(dir / "report.html") : nlohmann::json();
  if (report.is_object() && report.contains("view") && report["view"].contains("ground_truth"))
    u.ground_truth = trajectoryOf(report["view"]["ground_truth"]);
  if (report.is_object() && report.contains("view") && report["view"].contains("culled"))
    u.map.culled = pointsOf(report["view"]["culled"]);
  info["has_ground_truth"] = u.ground_truth.has_value() && !u.ground_truth->empty();
  u.info = info;
  state.setFiles(overlaysOf(dir, report));
  loadDenseLayers(dir, state);
  state.apply(u);
}

}  // namespace amos::viewer
