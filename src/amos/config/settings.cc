#include "amos/config/settings.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "amos/config/dynamic_section.h"
#include "amos/config/slam_section.h"
#include "amos/config/yaml_reader.h"
#include "amos/core/error.h"

namespace amos::config {

namespace {

void readCamera(YamlReader& in, Settings& s) {
  auto& c = s.camera;
  in.read("Camera.fx", c.fx);
  in.read("Camera.fy", c.fy);
  in.read("Camera.cx", c.cx);
  in.read("Camera.cy", c.cy);
  in.read("Camera.k1", c.k1);
  in.read("Camera.k2", c.k2);
  in.read("Camera.p1", c.p1);
  in.read("Camera.p2", c.p2);
  in.read("Camera.k3", c.k3);
  in.read("Camera.width", c.width);
  in.read("Camera.height", c.height);
  in.read("Camera.fps", s.fps);
  in.read("Camera.RGB", s.rgb_order);
  in.read("Camera.bf", s.bf);
  in.read("ThDepth", s.th_depth);
  in.read("DepthMapFactor", s.depth_factor);
  for (const char* key : {"Camera.fx", "Camera.fy", "Camera.cx", "Camera.cy"}) {
    core::require(in.has(key), fmt::format("{}: required key '{}' is missing", in.path(), key));
  }
}

void readOrb(YamlReader& in, feature::OrbOptions& o) {
  in.read("ORBextractor.nFeatures", o.num_features);
  in.read("ORBextractor.scaleFactor", o.scale_factor);
  in.read("ORBextractor.nLevels", o.num_levels);
  in.read("ORBextractor.iniThFAST", o.ini_fast_threshold);
  in.read("ORBextractor.minThFAST", o.min_fast_threshold);
}

void readProjectKeys(YamlReader& in, Settings& s) {
  std::string gt = "tum";
  in.read("Dataset.groundtruth", gt);
  if (gt == "tum") s.groundtruth_format = GroundTruthFormat::kTum;
  else if (gt == "bonn") s.groundtruth_format = GroundTruthFormat::kBonn;
  else throw core::Error(fmt::format("{}: Dataset.groundtruth must be 'tum' or 'bonn', got '{}'",
                                     in.where("Dataset.groundtruth"), gt));
}

// Option structs name the key they reject; add the file and line of that key to the message.
void checkWithLocation(const Settings& s, const YamlReader& in) {
  try {
    s.check();
  } catch (const core::Error& e) {
    const std::string message = e.what();
    for (const auto& key : in.keys()) {
      if (message.find(key) != std::string::npos) throw core::Error(fmt::format("{}: {}", in.where(key), message));
    }
    throw core::Error(fmt::format("{}: {}", in.path(), message));
  }
}

Settings parse(YamlReader in) {
  Settings s;
  s.source_file = in.path();
  readCamera(in, s);
  readOrb(in, s.orb);
  readProjectKeys(in, s);
  readTrackingSection(in, s.fps, s.tracking);
  readMappingSection(in, s.mapping, s.covisibility);
  readLoopSection(in, s.mapping, s.loop);
  readDynamicSection(in, s.dynamic);
  readSegmentationSection(in, s.segmentation);
  checkWithLocation(s, in);
  for (const auto& key : in.unreadKeys()) spdlog::warn("{}: unknown key '{}' ignored", in.where(key), key);
  return s;
}

}  // namespace

void Settings::check() const {
  camera.check();
  core::require(fps > 0, fmt::format("Camera.fps must be positive, got {}", fps));
  core::require(bf > 0, fmt::format("Camera.bf must be positive, got {}", bf));
  core::require(th_depth > 0, fmt::format("ThDepth must be positive, got {}", th_depth));
  core::require(depth_factor > 0, fmt::format("DepthMapFactor must be positive, got {}", depth_factor));
  orb.check();
  tracking.check();
  mapping.check();
  this->loop.check();
  core::require(covisibility.min_weight >= 1, "Mapping.covisibilityMinWeight must be >= 1");
  dynamic.check();
  segmentation.check();
}

io::ReaderOptions Settings::readerOptions() const {
  io::ReaderOptions o;
  o.depth_factor = depth_factor;
  o.width = camera.width;
  o.height = camera.height;
  return o;
}

Settings loadSettings(const std::string& path) { return parse(YamlReader::fromFile(path)); }

Settings parseSettings(const std::string& yaml_text, const std::string& virtual_path) {
  return parse(YamlReader::fromText(yaml_text, virtual_path));
}

}  // namespace amos::config
