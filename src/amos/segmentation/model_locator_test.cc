#include "amos/segmentation/model_locator.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "amos/core/error.h"
#include "amos/testing/scratch_dir.h"

namespace amos::segmentation {
namespace {

const std::vector<std::string> kFiles = {"det.onnx", "mask.onnx"};

// A fake file system holding both files in each of `dirs`.
FileExists filesIn(std::set<std::string> dirs) {
  return [dirs](const std::string& path) {
    for (const auto& dir : dirs)
      for (const auto& f : kFiles)
        if (path == joinPath(dir, f)) return true;
    return false;
  };
}

EnvironmentLookup envWith(const std::string& amos_models) {
  return [amos_models](const std::string& name) -> std::optional<std::string> {
    if (name == "AMOS_MODELS") return amos_models;
    return std::nullopt;
  };
}

std::string errorOf(const ModelSources& sources, const FileExists& exists) {
  try {
    locateModelDir(sources, kFiles, exists);
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

TEST(ModelLocator, OrderIsCliSettingsEnvironmentThenDefaults) {
  const auto all = filesIn({"/cli", "/settings", "/env", "./models", "../shared/models"});
  ModelSources s{"/cli", "/settings", envWith("/env")};
  EXPECT_EQ(locateModelDir(s, kFiles, all).dir, "/cli");
  EXPECT_EQ(locateModelDir(s, kFiles, all).source, "--models");
  s.cli_dir.clear();
  EXPECT_EQ(locateModelDir(s, kFiles, all).dir, "/settings");
  EXPECT_EQ(locateModelDir(s, kFiles, all).source, "Segmentation.modelsDir");
  s.settings_dir.clear();
  EXPECT_EQ(locateModelDir(s, kFiles, all).dir, "/env");
  EXPECT_EQ(locateModelDir(s, kFiles, all).source, "AMOS_MODELS");
  s.environment = envWith("");  // set but empty counts as unset
  EXPECT_EQ(locateModelDir(s, kFiles, all).dir, "./models");
  s.environment = nullptr;
  EXPECT_EQ(locateModelDir(s, kFiles, filesIn({"../shared/models"})).dir, "../shared/models");
  EXPECT_EQ(locateModelDir(s, kFiles, filesIn({"../shared/models"})).source, "default ../shared/models");
}

TEST(ModelLocator, AnExplicitFolderWithoutTheModelIsAnErrorNotAFallThrough) {
  const auto defaults_only = filesIn({"./models"});
  const std::string message = errorOf({"/somewhere", "", nullptr}, defaults_only);
  EXPECT_NE(message.find("--models = '/somewhere'"), std::string::npos) << message;
  EXPECT_NE(message.find("det.onnx"), std::string::npos) << message;
  const std::string env_message = errorOf({"", "", envWith("/env")}, defaults_only);
  EXPECT_NE(env_message.find("AMOS_MODELS = '/env'"), std::string::npos) << env_message;
  // Only one of two files present: the missing one is named.
  const FileExists half = [](const std::string& p) { return p == "/cli/det.onnx"; };
  const std::string half_message = errorOf({"/cli", "", nullptr}, half);
  EXPECT_NE(half_message.find("does not hold mask.onnx"), std::string::npos) << half_message;
}

TEST(ModelLocator, NoModelAnywhereSaysWhatToDo) {
  const std::string message = errorOf({"", "", nullptr}, filesIn({}));
  ASSERT_FALSE(message.empty());
  for (const char* hint : {"--models", "Segmentation.modelsDir", "AMOS_MODELS", "./models", "../shared/models",
                           "--mode geometry", "det.onnx, mask.onnx"})
    EXPECT_NE(message.find(hint), std::string::npos) << hint << " missing in: " << message;
}

TEST(ModelLocator, RealFileSystem) {
  namespace fs = std::filesystem;
  const fs::path dir = testing::scratchDirForThisTest("amos_model_locator_");
  for (const auto& f : kFiles) std::ofstream(dir / f) << "x";
  ModelSources s;
  s.cli_dir = dir.string();
  EXPECT_EQ(locateModelDir(s, kFiles).dir, dir.string());
  fs::remove(dir / "mask.onnx");
  EXPECT_THROW(locateModelDir(s, kFiles), core::Error);
}

TEST(ModelLocator, JoinPath) {
  EXPECT_EQ(joinPath("a", "b.onnx"), "a/b.onnx");
  EXPECT_EQ(joinPath("a/", "b.onnx"), "a/b.onnx");
  EXPECT_EQ(joinPath("", "b.onnx"), "b.onnx");
}

}  // namespace
}  // namespace amos::segmentation
