#include "amos/viewer/run_folder.h"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "amos/core/error.h"
#include "amos/io/trajectory.h"
#include "amos/viewer/whole_file.h"

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

// The vertices of an ASCII PLY as written by report::writeMapPly ("x y z" per vertex).
std::vector<PointSample> readPlyPoints(const fs::path& path) {
  std::vector<PointSample> points;
  std::ifstream in(path);
  std::string line;
  std::size_t vertices = 0;
  while (std::getline(in, line) && line.rfind("end_header", 0) != 0) {
    std::istringstream words(line);
    std::string a, b;
    words >> a >> b;
    if (a == "element" && b == "vertex") words >> vertices;
  }
  for (std::size_t i = 0; i < vertices && std::getline(in, line); ++i) {
    std::istringstream words(line);
    PointSample p;
    p.id = i;
    if (words >> p.position.x() >> p.position.y() >> p.position.z()) points.push_back(p);
  }
  return points;
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
      const nlohmann::json stats = nlohmann::json::parse(readWholeFile(dir / "stats.json"));
      u.summary = stats;
      for (const char* key : {"sequence", "mode", "config"})
        if (stats.contains(key)) info[key] = stats[key];
      if (stats.contains("frames")) info["frames"] = stats["frames"];
    } catch (const nlohmann::json::exception& e) {
      throw core::Error(fmt::format("view: {}: not valid JSON: {}", (dir / "stats.json").string(), e.what()));
    }
  }
  u.info = info;
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
  if (fs::exists(dir / "map.ply")) u.map.points = readPlyPoints(dir / "map.ply");
  nlohmann::json overlays = nlohmann::json::array();
  if (fs::is_directory(dir / "overlays")) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir / "overlays"))
      if (e.is_regular_file() && e.path().extension() == ".png") names.push_back("overlays/" + e.path().filename().string());
    std::sort(names.begin(), names.end());
    overlays = names;
  }
  state.setFiles(std::move(overlays));
  state.apply(u);
}

}  // namespace amos::viewer
