#include "amos/rosbag/bag_settings.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <utility>
#include <vector>

#include "amos/config/yaml_reader.h"
#include "amos/core/error.h"
#include "amos/core/whole_file.h"

namespace amos::rosbag {

namespace {

const char* const kFocalKeys[] = {"Camera.fx", "Camera.fy", "Camera.cx", "Camera.cy"};

std::vector<std::pair<std::string, double>> calibrationKeys(const core::CameraIntrinsics& c) {
  return {{"Camera.fx", c.fx}, {"Camera.fy", c.fy}, {"Camera.cx", c.cx}, {"Camera.cy", c.cy},
          {"Camera.k1", c.k1}, {"Camera.k2", c.k2}, {"Camera.p1", c.p1}, {"Camera.p2", c.p2},
          {"Camera.k3", c.k3}, {"Camera.width", static_cast<double>(c.width)},
          {"Camera.height", static_cast<double>(c.height)}};
}

std::string fileText(const std::string& path) {
  return core::readWholeFileOrThrow(path, fmt::format("settings file '{}' cannot be read", path));
}

void warnWhenTheyDiffer(const config::Settings& settings, const core::CameraIntrinsics& info,
                        const std::string& path, const std::string& source) {
  const core::CameraIntrinsics& c = settings.camera;
  constexpr double kPixels = 0.5;  // below any calibration's own uncertainty
  if (std::abs(c.fx - info.fx) < kPixels && std::abs(c.fy - info.fy) < kPixels && std::abs(c.cx - info.cx) < kPixels &&
      std::abs(c.cy - info.cy) < kPixels)
    return;
  spdlog::warn("{} gives fx {} fy {} cx {} cy {}, the settings '{}' fx {} fy {} cx {} cy {}: the settings are used",
               source, info.fx, info.fy, info.cx, info.cy, path, c.fx, c.fy, c.cx, c.cy);
}

}  // namespace

bool settingsHaveCalibration(const std::string& path) {
  const config::YamlReader file = config::YamlReader::fromFile(path);
  bool any_focal = false;
  for (const char* key : kFocalKeys) any_focal = any_focal || file.has(key);
  return any_focal;
}

std::string settingsTextWithCamera(const std::string& path, const std::optional<core::CameraIntrinsics>& camera_info,
                                   const std::string& camera_info_source) {
  std::string text = fileText(path);
  if (settingsHaveCalibration(path)) return text;
  const config::YamlReader file = config::YamlReader::fromFile(path);
  core::require(camera_info.has_value(),
                fmt::format("settings '{}' give no camera calibration (Camera.fx, fy, cx, cy) and {} has no "
                            "camera_info message: add the calibration to the settings or record camera_info",
                            path, camera_info_source));
  text += fmt::format("\n# from {}\n", camera_info_source);
  for (const auto& [key, value] : calibrationKeys(*camera_info)) {
    if (!file.has(key)) text += fmt::format("{}: {}\n", key, value);
  }
  spdlog::info("camera calibration from {}: fx {} fy {} cx {} cy {}", camera_info_source, camera_info->fx,
               camera_info->fy, camera_info->cx, camera_info->cy);
  return text;
}

config::Settings settingsForBag(const std::string& path, const std::optional<core::CameraIntrinsics>& camera_info,
                                const std::string& camera_info_source, const config::SectionRegistry& added) {
  const config::Settings settings =
      config::parseSettings(settingsTextWithCamera(path, camera_info, camera_info_source), path, added);
  if (camera_info) warnWhenTheyDiffer(settings, *camera_info, path, camera_info_source);
  return settings;
}

}  // namespace amos::rosbag
