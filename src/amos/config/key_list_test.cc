#include "amos/config/key_list.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include "amos/config/settings.h"
#include "amos/config/test_settings.h"
#include "amos/core/error.h"
#include "amos/core/log_capture.h"

namespace amos::config {
namespace {

using namespace test_settings;

// name -> value of every key of `s`.
std::map<std::string, std::string> valuesOf(Settings& s) {
  std::map<std::string, std::string> out;
  for (const auto& section : settingsKeys(s)) {
    for (const auto& key : section.keys) out[key.name()] = key.value();
  }
  return out;
}

std::vector<std::string> listedNames() {
  Settings s = defaultSettings(addedSections());
  std::vector<std::string> out;
  for (const auto& section : settingsKeys(s)) {
    for (const auto& key : section.keys) out.push_back(key.name());
  }
  return out;
}

bool sameValue(const SettingsKey& key, const std::string& a, const std::string& b) {
  if (key.kind() != SettingsKey::Kind::kNumber) return a == b;
  const double x = std::stod(a), y = std::stod(b);
  return std::abs(x - y) <= 1e-6 * std::max(1.0, std::abs(y));  // float members keep ~7 digits
}

// Values other than `current` to try for a key, most likely valid first.
std::vector<std::string> otherValues(const SettingsKey& key, const std::string& current) {
  std::vector<std::string> out;
  switch (key.kind()) {
    case SettingsKey::Kind::kNumber: {
      const double v = std::stod(current);
      for (double c : {v * 1.5, v * 0.5, v + 1, v - 1, 0.5, 2.0, v * 1.1}) out.push_back(fmt::format("{}", c));
      break;
    }
    case SettingsKey::Kind::kWholeNumber: {
      const long v = std::stol(current);
      for (long step = 1; step <= 256; ++step) {
        out.push_back(std::to_string(v + step));
        if (v - step >= 0) out.push_back(std::to_string(v - step));
      }
      break;
    }
    case SettingsKey::Kind::kFlag:
      out.push_back(current == "1" ? "0" : "1");
      break;
    case SettingsKey::Kind::kText:
      out = {"frame", "rect", "square", "ellipse", "/tmp/amos_models"};
      break;
    case SettingsKey::Kind::kList:
      out = {"[person, chair]", "[chair]"};
      break;
    case SettingsKey::Kind::kChoice:
      out = key.choices();
      break;
  }
  out.erase(std::remove_if(out.begin(), out.end(), [&](const std::string& c) { return sameValue(key, c, current); }),
            out.end());
  return out;
}

// Each key, set alone in a file to a valid value other than its default, changes its member and no other
// (but for the keys whose default follows it: Tracking.maxFrames follows Camera.fps, Tracking.closeTrackedMax
// ORBextractor.nFeatures).
TEST(SettingsKeys, EveryListedKeyIsReadIntoItsOwnMember) {
  Settings base = parseSettings(yamlOf(kRequired), "base.yaml", addedSections());
  const std::map<std::string, std::string> base_values = valuesOf(base);
  std::size_t checked = 0;
  for (const auto& section : settingsKeys(base)) {
    for (const SettingsKey& key : section.keys) {
      std::optional<Settings> changed;
      std::string value;
      for (const std::string& candidate : otherValues(key, key.value())) {
        std::map<std::string, std::string> file = kRequired;
        file[key.name()] = candidate;
        try {
          changed = parseSettings(yamlOf(file), "t.yaml", addedSections());
          value = candidate;
          break;
        } catch (const core::Error&) {
          // not a valid value of this key; try the next
        }
      }
      if (!changed) {
        ADD_FAILURE() << key.name() << ": no valid value other than " << key.value() << " found to set it to";
        continue;
      }
      for (const auto& changed_section : settingsKeys(*changed)) {
        for (const SettingsKey& other : changed_section.keys) {
          if (other.name() == key.name()) {
            EXPECT_TRUE(sameValue(other, other.value(), value))
                << key.name() << ": " << value << " in the file, " << other.value() << " in its member: not read";
          } else if (other.defaultValue().rfind(key.name(), 0) != 0) {  // its default is not derived from this key
            EXPECT_EQ(other.value(), base_values.at(other.name()))
                << "setting " << key.name() << " changed " << other.name();
          }
        }
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, listedNames().size());
}

// Values that are likely invalid for a key of this kind.
std::vector<std::string> badValues(const SettingsKey& key) {
  switch (key.kind()) {
    case SettingsKey::Kind::kNumber:
      return {"-1", "0", "-1000", "1e9", "many"};
    case SettingsKey::Kind::kWholeNumber:
      return {"-1", "0", "100000", "1.5", "many"};
    case SettingsKey::Kind::kFlag:
      return {"2", "maybe"};
    case SettingsKey::Kind::kText:
    case SettingsKey::Kind::kChoice:
      return {"bogus", "[a, b]"};
    case SettingsKey::Kind::kList:
      return {"[unicorn]", "[]", "{a: 1}"};
  }
  return {};
}

// Whatever a key's invalid value breaks (its type, its own rule or a rule relating it to another key), the error
// names the file, the key's line and the key; related members are named by their keys too.
TEST(SettingsKeys, EveryInvalidValueIsAnErrorNamingFileLineAndKey) {
  Settings s = defaultSettings(addedSections());
  std::size_t rejected = 0;
  for (const auto& section : settingsKeys(s)) {
    for (const SettingsKey& key : section.keys) {
      for (const std::string& bad : badValues(key)) {
        std::map<std::string, std::string> file = kRequired;
        file[key.name()] = bad;
        const auto line = std::distance(file.begin(), file.find(key.name())) + 1;
        try {
          parseSettings(yamlOf(file), "t.yaml", addedSections());
        } catch (const core::Error& e) {
          const std::string message = e.what();
          EXPECT_EQ(message.rfind(fmt::format("t.yaml:{}: ", line), 0), 0u)
              << key.name() << ": " << bad << ": " << message;
          EXPECT_NE(message.find(key.name()), std::string::npos) << key.name() << ": " << bad << ": " << message;
          ++rejected;
        }
      }
    }
  }
  EXPECT_GT(rejected, listedNames().size());
}

TEST(SettingsKeys, ARuleRelatingTwoKeysNamesBoth) {
  const std::pair<std::string, std::string> cases[] = {
      {"Dynamic.Prior.lag: 5\n", "t.yaml:5: Dynamic.Prior.lag (5) must not exceed Dynamic.Prior.interval (3)"},
      {"Dynamic.Prior.interval: 1\n", "t.yaml:5: Dynamic.Prior.lag (2) must not exceed Dynamic.Prior.interval (1)"},
      {"Tracking.localMinInliers: 60\n",
       "t.yaml:5: Tracking.relocMinInliers must be >= Tracking.localMinInliers = 60, got 50"},
      {"Camera.width: 300\n",
       "t.yaml:1: Camera.cx must lie in [0, Camera.width = 300], got 320 (see Camera.width at "
       "t.yaml:5)"},
  };
  for (const auto& [line, expected] : cases) {
    try {
      parseSettings(yamlOf(kRequired) + line, "t.yaml", addedSections());
      ADD_FAILURE() << line << " passed";
    } catch (const core::Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << e.what();
    }
  }
}

TEST(SettingsKeys, NamesAreUniqueMembersTooAndOfOneStyle) {
  Settings s = defaultSettings(addedSections());
  std::set<std::string> names;
  std::set<const void*> members;
  // Section(s).lowerCamelName; ORB-SLAM2's own keys keep their spelling, since users' files use them.
  const std::regex style(R"(([A-Z][A-Za-z]*\.)+[a-z][A-Za-z0-9]*)");
  const std::set<std::string> orb_slam2 = {"ThDepth", "DepthMapFactor", "Camera.RGB"};
  for (const auto& section : settingsKeys(s)) {
    for (const auto& key : section.keys) {
      EXPECT_TRUE(names.insert(key.name()).second) << key.name() << " is listed twice";
      for (const auto& old : key.formerNames()) EXPECT_TRUE(names.insert(old).second) << old << " is listed twice";
      EXPECT_TRUE(members.insert(key.member()).second) << key.name() << " sets a member another key sets";
      EXPECT_TRUE(std::regex_match(key.name(), style) || orb_slam2.count(key.name())) << key.name();
      EXPECT_FALSE(key.description().empty()) << key.name();
      EXPECT_EQ(key.description().find('\n'), std::string::npos) << key.name();
    }
  }
}

TEST(SettingsKeys, RequiredKeysMustBeSet) {
  try {
    parseSettings("Camera.fx: 500\nCamera.fy: 500\nCamera.cx: 320\n", "t.yaml", addedSections());
    FAIL() << "a file without Camera.cy passed";
  } catch (const core::Error& e) {
    EXPECT_STREQ(e.what(), "t.yaml: required key 'Camera.cy' is missing");
  }
}

TEST(SettingsKeys, ANegativeSeedIsAWrongType) {
  try {
    parseSettings(yamlOf(kRequired) + "Dynamic.Cluster.seed: -1\n", "t.yaml", addedSections());
    FAIL() << "a negative seed passed";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("t.yaml:5: key 'Dynamic.Cluster.seed' must be a whole number >= 0"),
              std::string::npos)
        << e.what();
  }
}

// Segmentation's keys were snake_case where every other section's are lowerCamelCase; the old names still work.
TEST(SettingsKeys, AFormerNameIsReadWithAWarningGivingTheNewName) {
  core::LogCapture log;
  const Settings s =
      parseSettings(yamlOf(kRequired) + "Segmentation.models_dir: /opt/models\n", "t.yaml", addedSections());
  EXPECT_EQ(s.segmentation.models_dir, "/opt/models");
  const auto lines = log.lines();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("t.yaml:5: key 'Segmentation.models_dir' is deprecated: it is now called "
                          "'Segmentation.modelsDir'"),
            std::string::npos)
      << lines[0];
  try {
    parseSettings(yamlOf(kRequired) + "Segmentation.modelsDir: /a\nSegmentation.models_dir: /b\n", "t.yaml",
                  addedSections());
    FAIL() << "both names passed";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("t.yaml:6: key 'Segmentation.models_dir' is the old name of "
                                         "'Segmentation.modelsDir', which is set too (t.yaml:5)"),
              std::string::npos)
        << e.what();
  }
}

TEST(SettingsKeys, EveryShippedConfigLoadsWithoutAWarning) {
  std::size_t configs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(AMOS_SOURCE_DIR) + "/configs")) {
    if (entry.path().extension() != ".yaml") continue;
    core::LogCapture log;
    EXPECT_NO_THROW(loadSettings(entry.path().string(), addedSections())) << entry.path();
    EXPECT_TRUE(log.lines().empty()) << entry.path() << ": " << log.lines().front();
    ++configs;
  }
  EXPECT_GE(configs, 4u);
}

// An experiment stays only while a shipped config turns it on (sets it to a value other than its default); one that
// no config uses is deleted, with a record in docs/experiments/ (the style guide's "options that end").
TEST(SettingsKeys, EveryExperimentalKeyIsTurnedOnInAShippedConfig) {
  Settings defaults = defaultSettings(addedSections());
  const std::map<std::string, std::string> default_values = valuesOf(defaults);
  std::map<std::string, std::vector<std::string>> turned_on;  // experimental key -> the configs that turn it on
  for (const auto& section : settingsKeys(defaults)) {
    for (const auto& key : section.keys)
      if (key.isExperimental()) turned_on[key.name()];
  }
  ASSERT_FALSE(turned_on.empty());
  for (const auto& entry : std::filesystem::directory_iterator(std::string(AMOS_SOURCE_DIR) + "/configs")) {
    if (entry.path().extension() != ".yaml") continue;
    Settings loaded = loadSettings(entry.path().string(), addedSections());
    const std::map<std::string, std::string> values = valuesOf(loaded);
    for (auto& [name, configs] : turned_on)
      if (values.at(name) != default_values.at(name)) configs.push_back(entry.path().filename().string());
  }
  for (const auto& [name, configs] : turned_on) {
    EXPECT_FALSE(configs.empty()) << name << " is experimental but every shipped config leaves it at its default ("
                                  << default_values.at(name)
                                  << "): turn it on in a config, make it a plain option, or delete it with a record "
                                     "in docs/experiments/";
  }
}

std::string readmeText() {
  std::ifstream in(std::string(AMOS_SOURCE_DIR) + "/configs/README.md");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(SettingsKeys, TheReadmeDocumentsExactlyTheListedKeys) {
  const std::string readme = readmeText();
  ASSERT_FALSE(readme.empty());
  std::set<std::string> documented;
  const std::regex row(R"(^\| `([^`]+)` \|)");
  std::istringstream lines(readme);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, row)) documented.insert(m[1]);
  }
  const std::vector<std::string> names = listedNames();
  const std::set<std::string> listed(names.begin(), names.end());
  for (const auto& key : documented) EXPECT_TRUE(listed.count(key)) << key << " is documented but not read";
  for (const auto& key : listed) EXPECT_TRUE(documented.count(key)) << key << " is read but not documented";
}

TEST(SettingsKeys, TheReadmeKeyTablesAreUpToDate) {
  const std::string readme = readmeText();
  EXPECT_EQ(withKeyTables(readme, addedSections()), readme)
      << "configs/README.md's key tables differ from the key lists: run amos-slam config --update-readme "
         "configs/README.md";
  EXPECT_THROW(withKeyTables("# no markers\n"), core::Error);
}

TEST(SettingsKeys, TheTablesShowDefaultsChoicesAndFormerNames) {
  const std::string tables = keysMarkdown(addedSections());
  for (const char* row : {
           "| `Camera.fx` | required | focal length along x (px) |",
           "| `Tracking.maxFrames` | `Camera.fps` |",
           "| `Dynamic.LK.epsilon` | `0.03` |",
           "| `Dynamic.Epipolar.maxIterations` | `2000` |",
           "| `Dynamic.mode` | `full` |",
           "(`none`, `prior`, `geometry`, `full`) |",
           "| `Segmentation.classes` | `[person]` |",
           "| `Segmentation.modelsDir` | `\"\"` |",
           "; formerly `Segmentation.models_dir` |",
           "| `LocalBA.enabled` | `1` |",
           "| `Dynamic.Depth.enabled` | `0` | *experimental:* superpixels",
       }) {
    EXPECT_NE(tables.find(row), std::string::npos) << row;
  }
}

}  // namespace
}  // namespace amos::config
