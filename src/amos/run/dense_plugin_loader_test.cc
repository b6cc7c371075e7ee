#include "amos/run/dense_plugin_loader.h"

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "amos/core/error.h"
#include "amos/testing/error_of.h"
#include "amos/testing/scratch_dir.h"

namespace amos::run {
namespace {

namespace fs = std::filesystem;
using testing::errorOf;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(DensePluginLoader, LooksBesideTheProgramThenInTheInstalledLibFolder) {
  const std::vector<fs::path> candidates = densePluginCandidates("/opt/amos/bin");
  ASSERT_EQ(candidates.size(), 2u);
  EXPECT_EQ(candidates[0], fs::path("/opt/amos/bin/libamos_dense_plugin.so"));
  EXPECT_EQ(candidates[1], fs::path("/opt/amos/lib/amos/libamos_dense_plugin.so"));
}

TEST(DensePluginLoader, AMissingModuleIsAnErrorNamingEveryPathTried) {
  const fs::path dir = testing::scratchDirForThisTest("dense_plugin_");
  const std::string error = errorOf([&] { DensePluginLibrary library(densePluginCandidates(dir / "bin")); });
  EXPECT_TRUE(contains(error, (dir / "bin" / kDensePluginFile).string())) << error;
  EXPECT_TRUE(contains(error, (dir / "lib" / "amos" / kDensePluginFile).string())) << error;
  EXPECT_TRUE(contains(error, "not found")) << error;
}

TEST(DensePluginLoader, ABrokenModuleIsAnErrorWithTheLoadersReason) {
  const fs::path dir = testing::scratchDirForThisTest("dense_plugin_");
  const fs::path broken = dir / kDensePluginFile;
  std::ofstream(broken) << "not a shared library\n";
  const std::string error = errorOf([&] { DensePluginLibrary library({dir / "absent.so", broken}); });
  EXPECT_TRUE(contains(error, "cannot load the dense map's module " + broken.string() + ": ")) << error;
  EXPECT_TRUE(contains(error, broken.string() + ": ")) << error;  // dlerror() names the file and says why
}

TEST(DensePluginLoader, ALibraryWithoutTheEntryPointIsRefused) {
  Dl_info info{};
  ASSERT_NE(dladdr(reinterpret_cast<void*>(&dlopen), &info), 0);  // libc (or libdl): loadable, no plugin in it
  const std::string error = errorOf([&] { DensePluginLibrary library({info.dli_fname}); });
  EXPECT_TRUE(contains(error, "has no entry point amos_dense_plugin")) << error;
}

#ifdef AMOS_HAVE_DENSE_PLUGIN
// The module built beside this test program (run/CMakeLists.txt), loaded as amos-slam loads it.
const DensePlugin& builtPlugin() {
  static const DensePluginLibrary library(densePluginCandidates(fs::read_symlink("/proc/self/exe").parent_path()));
  return library.plugin();
}

TEST(DensePluginLoader, TheBuiltModuleGivesTheDenseObserversFiles) {
  EXPECT_EQ(builtPlugin().denseOutputNames(),
            (std::vector<std::string>{"mesh.ply", "cloud.ply", "removed_points.ply", "occupancy.pgm", "occupancy.yaml"}));
  EXPECT_EQ(&densePlugin(), &densePlugin());  // loaded once
}

// core::Error thrown inside the module is caught as core::Error here, with the module's message: the same as the
// options' own check gives.
TEST(DensePluginLoader, TheModulesErrorsReachTheProgramAsCoreErrors) {
  dense::DenseOptions options;
  options.min_depth = 0.01;
  const std::string expected = errorOf([&] { options.check(); });
  ASSERT_FALSE(expected.empty());
  std::string caught;
  try {
    builtPlugin().makeDenseRunMap(options, "/nonexistent", {});
  } catch (const core::Error& e) {
    caught = e.what();
  }
  EXPECT_EQ(caught, expected);
}
#endif

}  // namespace
}  // namespace amos::run
