// amos::Options beyond the settings file (issue 52): overrides by key checked against the key registry, the Mode
// enumeration, where the models are looked for and how a missing one is reported, and the library's log.
#include <gtest/gtest.h>

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "amos/api/settings_overrides.h"
#include "amos/config/settings.h"
#include "amos/logging.h"
#include "amos/sequence_folder.h"
#include "amos/slam.h"
#include "amos/synth/sequence.h"
#include "amos/testing/error_of.h"
#include "amos/testing/scratch_dir.h"
#include "amos/testing/test_inputs.h"

namespace amos {
namespace {

namespace fs = std::filesystem;

using amos::testing::kTum3;

using amos::testing::errorOf;

TEST(SettingsOverrides, SetAKeyOverTheFileAndRefuseUnknownOnes) {
  const std::string yaml = "%YAML:1.0\nORBextractor.nFeatures: 1000\n  ORBextractor.nFeatures : 900\nCamera.fx: 1\n";
  const std::string out = api::withOverrides(yaml, {{"ORBextractor.nFeatures", "1500"}}, "opt");
  EXPECT_EQ(out, "%YAML:1.0\nCamera.fx: 1\nORBextractor.nFeatures: 1500\n");
  EXPECT_NE(errorOf([&] { api::withOverrides(yaml, {{"ORBextractor.nFeature", "1"}}, "opt"); })
                .find("opt: unknown settings key 'ORBextractor.nFeature'"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { api::withOverrides(yaml, {{"Camera.fx", "1\nCamera.fy: 2"}}, "opt"); })
                .find("must be one non-empty line"),
            std::string::npos);
}

TEST(SettingsOverrides, ReachTheSlamsSettings) {
  Options o;
  o.settings_file = kTum3;
  o.mode = Mode::kNone;
  o.overrides = {{"Camera.width", "700"}, {"Camera.height", "500"}};
  const Slam slam(o);
  EXPECT_EQ(slam.imageSize(), cv::Size(700, 500));
  o.overrides = {{"Camera.widht", "320"}};
  EXPECT_NE(errorOf([&] { Slam{o}; }).find("amos::Options::overrides: unknown settings key 'Camera.widht'"),
            std::string::npos);
  o.overrides = {{"Camera.width", "wide"}};
  EXPECT_NE(errorOf([&] { Slam{o}; }).find("Camera.width"), std::string::npos);
}

TEST(SlamOptions, ModesByEnumerationAndName) {
  EXPECT_EQ(parseMode("geometry"), Mode::kGeometry);
  EXPECT_EQ(parseMode(""), Mode::kFromSettings);
  EXPECT_STREQ(toString(Mode::kFull), "full");
  EXPECT_NE(errorOf([] { parseMode("fast"); }).find("mode 'fast' is not one of"), std::string::npos);
}

// A missing model is reported in the API's words (the option to set), not the command line's.
TEST(SlamOptions, AMissingModelNamesTheOptionToSet) {
  Options o;
  o.settings_file = kTum3;
  o.mode = Mode::kPrior;
  o.models_dir = "/nonexistent/models";
  const std::string message = errorOf([&] { Slam{o}; });
  EXPECT_NE(message.find("Options::models_dir = '/nonexistent/models'"), std::string::npos) << message;
  EXPECT_EQ(message.find("--models"), std::string::npos) << message;
  EXPECT_EQ(message.find("--mode"), std::string::npos) << message;
}

// The caller's sink receives the library's messages of the level set, from whichever thread logs them.
TEST(Logging, TheCallersSinkReceivesTheMessagesOfItsLevel) {
  std::mutex mutex;
  std::vector<std::pair<LogLevel, std::string>> got;
  setLogging(LogLevel::kWarn, [&](LogLevel level, const std::string& message) {
    std::lock_guard lock(mutex);
    got.emplace_back(level, message);
  });
  spdlog::info("not wanted");
  spdlog::warn("wanted {}", 1);
  // A folder with a frame that cannot be read warns from its reading thread.
  const fs::path dir = testing::scratchDirForThisTest("amos_api_") / "seq";
  fs::copy(synth::cachedSequence((fs::path(AMOS_BINARY_DIR) / "test_outputs" / "api_sequences").string(),
                                 "walking_xyz", 1, 30),
           dir, fs::copy_options::recursive);
  std::ofstream(SequenceFolder(dir.string()).read(2).rgb_file, std::ios::trunc) << "x";
  SequenceFolder folder(dir.string());
  while (folder.next()) {
  }
  setLogging(LogLevel::kWarn);  // back to stderr before `got` goes
  ASSERT_GE(got.size(), 2u);
  EXPECT_EQ(got[0], std::make_pair(LogLevel::kWarn, std::string("wanted 1")));
  EXPECT_EQ(got[1].first, LogLevel::kWarn);
  EXPECT_NE(got[1].second.find("frame 2 skipped"), std::string::npos) << got[1].second;
  EXPECT_STREQ(toString(LogLevel::kInfo), "info");
}

}  // namespace
}  // namespace amos
