#include "amos/config/slam_options.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "amos/core/stage_timer.h"
#include "amos/segmentation/model_locator.h"

namespace amos::config {

namespace fs = std::filesystem;

system::SlamOptions slamOptionsFromSettings(const Settings& settings, bool deterministic, const std::string& models_dir) {
  system::SlamOptions o;
  o.camera = settings.camera;
  o.sensor.bf = settings.bf;
  o.sensor.th_depth = settings.th_depth;
  o.orb = settings.orb;
  o.tracking = settings.tracking;
  o.mapping = settings.mapping;
  o.loop = settings.loop;
  o.covisibility = settings.covisibility;
  o.deterministic = deterministic;
  o.vocabulary = loadPlaceVocabulary(settings, models_dir);
  return o;
}

std::shared_ptr<const place::Vocabulary> loadPlaceVocabulary(const Settings& settings, const std::string& models_dir) {
  const std::string& name = settings.place_vocabulary;
  if (name.empty()) return nullptr;
  std::vector<std::string> tried{name};
  if (!fs::exists(name)) {
    std::vector<std::string> dirs;
    if (!models_dir.empty()) dirs.push_back(models_dir);
    if (!settings.segmentation.models_dir.empty()) dirs.push_back(settings.segmentation.models_dir);
    if (const char* env = std::getenv("AMOS_MODELS"); env != nullptr && *env != 0) dirs.emplace_back(env);
    dirs.emplace_back("./models");
    dirs.emplace_back("../shared/models");
    for (const std::string& dir : dirs) tried.push_back(segmentation::joinPath(dir, name));
  }
  for (const std::string& path : tried) {
    if (!fs::is_regular_file(path)) continue;
    core::Stopwatch watch;
    auto vocabulary = std::make_shared<const place::Vocabulary>(place::Vocabulary::load(path));
    spdlog::info("place vocabulary {}: {} words, loaded in {:.0f} ms", path, vocabulary->numWords(), watch.elapsedMs());
    return vocabulary;
  }
  spdlog::warn("Place.vocabulary {} not found (tried {}): keyframes are ranked by thumbnails", name,
               fmt::format("{}", fmt::join(tried, ", ")));
  return nullptr;
}

}  // namespace amos::config
