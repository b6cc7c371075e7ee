#include "amos/config/settings.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "amos/config/dynamic_section.h"
#include "amos/config/key_bounds.h"
#include "amos/config/slam_section.h"
#include "amos/config/yaml_reader.h"
#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::config {

namespace {

KeySection cameraKeys(Settings& s) {
  KeySection section{"Camera (ORB-SLAM2's keys)"};
  auto& c = s.camera;
  section.add("Camera.fx", &c.fx, "focal length along x (px)").required();
  section.add("Camera.fy", &c.fy, "focal length along y (px)").required();
  section.add("Camera.cx", &c.cx, "principal point, x (px)").required();
  section.add("Camera.cy", &c.cy, "principal point, y (px)").required();
  section.add("Camera.k1", &c.k1, "radial distortion (OpenCV's radial-tangential model)");
  section.add("Camera.k2", &c.k2, "radial distortion");
  section.add("Camera.p1", &c.p1, "tangential distortion");
  section.add("Camera.p2", &c.p2, "tangential distortion");
  section.add("Camera.k3", &c.k3, "radial distortion");
  section.add("Camera.width", &c.width, "image width (px); every frame must have it");
  section.add("Camera.height", &c.height, "image height (px)");
  section.add("Camera.fps", &s.fps, "frame rate (Hz)");
  section.add("Camera.RGB", &s.rgb_order, "1 = colour images are RGB (TUM and Bonn PNGs; OpenCV decodes them to BGR)");
  section.add("Camera.bf", &s.bf, "baseline (m) times fx of the virtual stereo camera RGB-D tracking uses");
  section.add("ThDepth", &s.th_depth, "close/far threshold in baselines: close below ThDepth x bf / fx metres");
  section.add("DepthMapFactor", &s.depth_factor, "raw 16-bit depth / DepthMapFactor = metres");
  return section;
}

KeySection orbKeys(feature::OrbOptions& o) {
  KeySection section{"ORB extractor (ORB-SLAM2's keys)"};
  section.add("ORBextractor.nFeatures", &o.num_features, "features per image");
  section.add("ORBextractor.scaleFactor", &o.scale_factor, "scale between pyramid levels");
  section.add("ORBextractor.nLevels", &o.num_levels, "pyramid levels");
  section.add("ORBextractor.iniThFAST", &o.ini_fast_threshold, "FAST threshold tried first");
  section.add("ORBextractor.minThFAST", &o.min_fast_threshold,
              "FAST threshold of the cells where `iniThFAST` finds no corner");
  return section;
}

KeySection datasetKeys(Settings& s) {
  KeySection section{"Dataset"};
  section.add("Dataset.groundtruth", &s.groundtruth_format,
              {{"tum", GroundTruthFormat::kTum}, {"bonn", GroundTruthFormat::kBonn}},
              "ground truth of sequences recorded with this camera: TUM camera poses or Bonn marker poses");
  return section;
}

KeySection placeKeys(Settings& s) {
  KeySection section{"Place recognition"};
  section.add("Place.vocabulary", &s.place_vocabulary,
              "bag-of-words vocabulary (`amos-slam vocab`) ranking keyframes for relocalisation and loop detection; "
              "a name that is not an existing path is looked for in $AMOS_MODELS, ./models, ../shared/models; \"\" = "
              "rank by thumbnails");
  return section;
}

// Replaces `word` in `text` where it stands alone (not inside a longer name).
std::string replaceName(std::string text, const std::string& word, const std::string& by) {
  auto part_of_name = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; };
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at)) {
    const bool alone = (at == 0 || !part_of_name(text[at - 1])) &&
                       (at + word.size() == text.size() || !part_of_name(text[at + word.size()]));
    if (!alone) {
      at += word.size();
      continue;
    }
    text.replace(at, word.size(), by);
    at += by.size();
  }
  return text;
}

// Runs s.check() and reports what it rejects by key: "file:line: Key rule", at the line of the key (or of a related
// key the file sets, or just the file when it sets neither), with the related members' names replaced by their keys
// and the lines of the related keys the file sets too.
void checkByKey(const Settings& s, const std::vector<KeySection>& sections, const YamlReader& in) {
  try {
    s.check();
  } catch (const core::InvalidOption& e) {
    const SettingsKey* key = keyOf(sections, e.field().address);
    if (key == nullptr) throw core::Error(fmt::format("{}: {}", in.path(), e.what()));  // no key sets that member
    std::string rule = e.rule();
    std::string where = key->nameIn(in);
    for (const core::OptionField& related : e.related()) {
      const SettingsKey* other = keyOf(sections, related.address);
      if (other == nullptr) continue;
      rule = replaceName(rule, related.name, other->name());
      const std::string other_name = other->nameIn(in);
      if (other_name.empty()) continue;
      if (where.empty()) {
        where = other_name;
      } else {
        rule += fmt::format(" (see {} at {})", other_name, in.where(other_name));
      }
    }
    throw core::Error(fmt::format("{}: {} {}", where.empty() ? in.path() : in.where(where), key->name(), rule));
  } catch (const core::Error& e) {
    throw core::Error(fmt::format("{}: {}", in.path(), e.what()));
  }
}

Settings parse(YamlReader in, const SectionRegistry& added) {
  Settings s = defaultSettings(added);
  s.source_file = in.path();
  const std::vector<KeySection> sections = settingsKeys(s);
  for (const auto& section : sections) {
    if (section.prepare) section.prepare();
    for (const auto& key : section.keys) key.read(in);
  }
  checkByKey(s, sections, in);
  for (const auto& key : in.unreadKeys()) spdlog::warn("{}: unknown key '{}' ignored", in.where(key), key);
  return s;
}

constexpr const char* kTablesBegin = "<!-- key tables: made by `amos-slam config --keys-markdown`, do not edit -->";
constexpr const char* kTablesEnd = "<!-- end of key tables -->";

}  // namespace

std::vector<KeySection> settingsKeys(Settings& s) {
  std::vector<KeySection> sections;
  sections.push_back(cameraKeys(s));
  sections.push_back(orbKeys(s.orb));
  sections.push_back(datasetKeys(s));
  sections.push_back(trackingKeys(s.tracking, s.fps, s.orb.num_features));
  sections.push_back(mappingKeys(s.mapping, s.covisibility));
  sections.push_back(loopKeys(s.loop, s.mapping));
  sections.push_back(placeKeys(s));
  sections.push_back(dynamicKeys(s.dynamic));
  sections.push_back(segmentationKeys(s.segmentation));
  applyKeyBounds(sections, s.camera);
  for (AddedSection& section : s.added) sections.push_back(section.keys());
  return sections;
}

Settings defaultSettings(const SectionRegistry& added) {
  Settings s;
  s.added = added.sections();
  return s;
}

std::string keysMarkdown(const SectionRegistry& added) {
  Settings defaults = defaultSettings(added);
  return keyTablesMarkdown(settingsKeys(defaults));
}

std::string withKeyTables(const std::string& readme, const SectionRegistry& added) {
  const auto begin = readme.find(kTablesBegin), end = readme.find(kTablesEnd);
  core::require(begin != std::string::npos && end != std::string::npos && begin < end,
                fmt::format("the settings README has no '{}' ... '{}' lines to put the key tables between",
                            kTablesBegin, kTablesEnd));
  const auto after_begin = readme.find('\n', begin) + 1;
  return readme.substr(0, after_begin) + "\n" + keysMarkdown(added) + readme.substr(end);
}

void Settings::check() const {
  using core::option;
  camera.check();
  // Bounds from the keys' meaning: a frame rate no camera exceeds; a virtual stereo baseline (bf / fx) of at most a
  // metre; a close/far threshold inside any depth sensor's range (50 m); a depth unit that resolves a centimetre
  // and lets 16 bits reach a metre.
  core::requireOption(fps > 0 && fps <= 1000, option(fps, "fps"), fmt::format("must be in (0, 1000] Hz, got {}", fps));
  core::requireOption(bf > 0 && bf <= camera.fx, option(bf, "bf"),
                      fmt::format("must be in (0, camera.fx] (a baseline of at most 1 m), got {}", bf),
                      {option(camera.fx, "camera.fx")});
  core::requireOption(th_depth > 0 && closeDepthThreshold() <= 50, option(th_depth, "th_depth"),
                      fmt::format("must be > 0 with th_depth x bf / camera.fx <= 50 m (the close/far threshold), got "
                                  "{} ({:.1f} m)",
                                  th_depth, closeDepthThreshold()),
                      {option(bf, "bf"), option(camera.fx, "camera.fx")});
  core::requireOption(depth_factor >= 100 && depth_factor <= 65535, option(depth_factor, "depth_factor"),
                      fmt::format("must be in [100, 65535] (raw units per metre: a centimetre resolved, a metre "
                                  "within 16 bits), got {}",
                                  depth_factor));
  orb.check();
  checkPyramid();
  tracking.check();
  mapping.check();
  this->loop.check();
  core::requireOption(covisibility.min_weight >= 1, option(covisibility.min_weight, "covisibility.min_weight"),
                      fmt::format("must be >= 1, got {}", covisibility.min_weight));
  dynamic.check();
  segmentation.check();
  for (const AddedSection& section : added) section.check(section.options, camera);
}

void Settings::checkPyramid() const {
  using core::option;
  // ORB's top pyramid level must still hold a FAST corner away from the descriptor's border (19 px each side).
  constexpr double kTopLevelMinSide = 40;
  const double top_side = std::min(camera.width, camera.height) / std::pow(orb.scale_factor, orb.num_levels - 1);
  core::requireOption(top_side >= kTopLevelMinSide, option(orb.num_levels, "orb.num_levels"),
                      fmt::format("leaves the top pyramid level {:.1f} px on the image's smaller side, fewer than {} "
                                  "(orb.scale_factor ^ (orb.num_levels - 1) must be at most camera.height / {})",
                                  top_side, kTopLevelMinSide, kTopLevelMinSide),
                      {option(orb.scale_factor, "orb.scale_factor"), option(camera.height, "camera.height"),
                       option(camera.width, "camera.width")});
}

io::ReaderOptions Settings::readerOptions() const {
  io::ReaderOptions o;
  o.depth_factor = depth_factor;
  o.width = camera.width;
  o.height = camera.height;
  return o;
}

Settings loadSettings(const std::string& path, const SectionRegistry& added) {
  return parse(YamlReader::fromFile(path), added);
}

Settings parseSettings(const std::string& yaml_text, const std::string& virtual_path, const SectionRegistry& added) {
  return parse(YamlReader::fromText(yaml_text, virtual_path), added);
}

}  // namespace amos::config
