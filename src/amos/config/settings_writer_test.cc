#include "amos/config/settings_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "amos/config/settings.h"

namespace amos::config {
namespace {

// Every key's value in `a` and in `b` (settingsKeys lists the same keys in the same order for both).
void expectSameValues(Settings a, Settings b) {
  const std::vector<KeySection> sa = settingsKeys(a), sb = settingsKeys(b);
  ASSERT_EQ(sa.size(), sb.size());
  std::size_t keys = 0;
  for (std::size_t i = 0; i < sa.size(); ++i) {
    ASSERT_EQ(sa[i].keys.size(), sb[i].keys.size()) << sa[i].title;
    for (std::size_t k = 0; k < sa[i].keys.size(); ++k, ++keys)
      EXPECT_EQ(sa[i].keys[k].value(), sb[i].keys[k].value()) << sa[i].keys[k].name();
  }
  EXPECT_GT(keys, 100u);
}

// Defaults but for the camera, which a settings file must give.
Settings minimal() {
  return parseSettings("Camera.fx: 500.0\nCamera.fy: 500.0\nCamera.cx: 320.0\nCamera.cy: 240.0\n", "minimal.yaml");
}

// Written with every key and read back by the normal reader: the same value for every key.
Settings roundTrip(const Settings& s) {
  const std::string text = settingsFileText(s, {"a comment"});
  return parseSettings(text, "settings_used.yaml");
}

TEST(SettingsWriter, WritesEveryKeyOnceWithTheCommentsOnTop) {
  Settings s;
  const std::string text = settingsFileText(s, {"command line: amos-slam run --mode full", "", "last"});
  EXPECT_EQ(text.rfind("%YAML:1.0\n# command line: amos-slam run --mode full\n#\n# last\n\n# ", 0), 0u) << text;
  std::size_t lines = 0;
  for (const KeySection& section : settingsKeys(s)) {
    for (const SettingsKey& key : section.keys) {
      const std::string line = "\n" + key.name() + ": ";
      const auto at = text.find(line);
      EXPECT_NE(at, std::string::npos) << key.name();
      EXPECT_EQ(text.find(line, at + 1), std::string::npos) << key.name();
      ++lines;
    }
  }
  EXPECT_GT(lines, 100u);
}

TEST(SettingsWriter, DefaultsReadBackTheSame) {
  const Settings defaults = minimal();
  expectSameValues(defaults, roundTrip(defaults));
}

TEST(SettingsWriter, ShippedConfigsReadBackTheSame) {
  for (const auto& e : std::filesystem::directory_iterator(std::string(AMOS_SOURCE_DIR) + "/configs")) {
    if (e.path().extension() != ".yaml") continue;
    SCOPED_TRACE(e.path().string());
    const Settings s = loadSettings(e.path().string());
    expectSameValues(s, roundTrip(s));
  }
}

// Values away from the defaults: numbers that need every digit, flags, choices, and text YAML would otherwise
// read as something else (quoted by the writer).
TEST(SettingsWriter, UnusualValuesReadBackTheSame) {
  Settings s = minimal();
  s.camera.fx = 517.3000000000001;
  s.camera.cx = 1.0 / 3.0;
  s.th_depth = 1.0 / 7.0;
  s.fps = 29.97;
  s.orb.scale_factor = 1.1 + 1e-12;
  s.rgb_order = false;
  s.groundtruth_format = GroundTruthFormat::kBonn;
  s.place_vocabulary = "";
  s.segmentation.models_dir = " a: b #c 'q' \"d\" \\e ";
  s.dynamic.mode = dynamic::DynamicMode::kGeometry;
  const Settings back = roundTrip(s);
  expectSameValues(s, back);
  EXPECT_EQ(back.segmentation.models_dir, s.segmentation.models_dir);
  EXPECT_EQ(back.camera.fx, s.camera.fx);
  EXPECT_EQ(back.camera.cx, s.camera.cx);
  EXPECT_EQ(back.orb.scale_factor, s.orb.scale_factor);
  EXPECT_EQ(back.place_vocabulary, "");
  EXPECT_EQ(back.dynamic.mode, dynamic::DynamicMode::kGeometry);
}

TEST(SettingsWriter, WritesTheFile) {
  const std::filesystem::path dir = std::filesystem::path(AMOS_BINARY_DIR) / "test_outputs" / "settings_writer";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "settings_used.yaml").string();
  Settings s = minimal();
  s.fps = 15;
  writeSettingsFile(path, s, {"written by a test"});
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
  const Settings back = loadSettings(path);
  EXPECT_EQ(back.fps, 15);
  expectSameValues(s, back);
}

}  // namespace
}  // namespace amos::config
