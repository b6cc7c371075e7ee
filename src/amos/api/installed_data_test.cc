#include "amos/api/installed_data.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "amos/testing/scratch_dir.h"

namespace amos::api {
namespace {

// A folder with the two files that mark a models folder.
std::string fakeModels() {
  const auto dir = testing::scratchDirForThisTest("amos_installed_");
  std::ofstream(dir / "orb_vocabulary.voc") << "x";
  std::ofstream(dir / "nanodet_m_320.onnx") << "x";
  return dir.string();
}

// The installed folder comes after every explicit source: the caller's, the settings', the environment's.
TEST(InstalledData, TheInstalledFolderIsTheDefaultAfterEveryExplicitSource) {
  const std::string installed = fakeModels();
  unsetenv("AMOS_MODELS");
  EXPECT_EQ(modelsFolder("/given", "", installed), "/given");
  EXPECT_EQ(modelsFolder("", "/from/settings", installed), "");
  EXPECT_EQ(modelsFolder("", "", installed), installed);
  EXPECT_EQ(modelsFolder("", "", "/nonexistent/models"), "");  // not an install: the usual search
  setenv("AMOS_MODELS", "/from/environment", 1);
  EXPECT_EQ(modelsFolder("", "", installed), "");
  unsetenv("AMOS_MODELS");
}

// A build tree is not an install: the test program (build/bin) has no share/amos-slam/models beside it.
TEST(InstalledData, ABuildTreeHasNoInstalledFolder) { EXPECT_EQ(installedModelsDir(), ""); }

}  // namespace
}  // namespace amos::api
