#include "amos/config/slam_options.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "amos/testing/scratch_dir.h"

namespace amos::config {
namespace {

namespace fs = std::filesystem;

// A folder holding a copy of the bundled vocabulary under a name no default folder has, so that only the folder
// under test can give it.
fs::path folderWithVocabulary() {
  const fs::path dir = testing::scratchDirForThisTest("slam_options_");
  fs::copy_file(fs::path(AMOS_SOURCE_DIR) / "models" / "orb_vocabulary.voc", dir / "only_here.voc");
  return dir;
}

Settings settingsNaming(const std::string& vocabulary) {
  Settings s;
  s.place_vocabulary = vocabulary;
  return s;
}

TEST(PlaceVocabulary, IsFoundInTheModelsFolderOfTheCommandLine) {
  const fs::path dir = folderWithVocabulary();
  EXPECT_EQ(loadPlaceVocabulary(settingsNaming("only_here.voc")), nullptr);  // no folder given: not found
  const auto vocabulary = loadPlaceVocabulary(settingsNaming("only_here.voc"), dir.string());
  ASSERT_NE(vocabulary, nullptr);
  EXPECT_GT(vocabulary->numWords(), 0u);
  EXPECT_NE(slamOptionsFromSettings(settingsNaming("only_here.voc"), true, dir.string()).vocabulary, nullptr);
}

TEST(PlaceVocabulary, IsFoundInTheSettingsModelsFolder) {
  const fs::path dir = folderWithVocabulary();
  Settings s = settingsNaming("only_here.voc");
  s.segmentation.models_dir = dir.string();
  EXPECT_NE(loadPlaceVocabulary(s), nullptr);
}

TEST(PlaceVocabulary, AnEmptyNameMeansThumbnails) {
  EXPECT_EQ(loadPlaceVocabulary(settingsNaming(""), folderWithVocabulary().string()), nullptr);
}

}  // namespace
}  // namespace amos::config
