#include "amos/testing/scratch_dir.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "amos/testing/file_text.h"

namespace amos::testing {
namespace {

namespace fs = std::filesystem;

struct ProbeRun {
  int status = 0;
  fs::path folder;  // the scratch folder the probe printed
  std::string err;
};

// Runs one case of the probe program (scratch_dir_probe.cc) in its own process.
ProbeRun runProbe(const std::string& test_case) {
  const fs::path err_file = scratchDirForThisTest("amos_scratch_") / "stderr.txt";
  const std::string command =
      std::string(AMOS_SCRATCH_PROBE) + " --gtest_filter=ScratchDirProbe." + test_case + " 2> '" + err_file.string() + "'";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof(buffer), pipe.get()) != nullptr) out += buffer;
  ProbeRun run;
  run.status = pclose(pipe.release());
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind(fs::temp_directory_path().string(), 0) == 0) run.folder = line;
  run.err = fileText(err_file.string());
  return run;
}

TEST(ScratchDir, IsEmptyAndInOneFolderOfThisProcess) {
  const fs::path a = scratchDir("amos_scratch_a");
  std::ofstream(a / "file.txt") << "x";
  const fs::path again = scratchDir("amos_scratch_a");
  EXPECT_EQ(again, a);
  EXPECT_TRUE(fs::is_empty(again));
  const fs::path b = scratchDir("amos_scratch_b");
  EXPECT_EQ(a.parent_path(), b.parent_path());
  EXPECT_EQ(a.parent_path().filename().string(), "amos_tests_" + std::to_string(static_cast<long>(::getpid())));
}

TEST(ScratchDir, IsRemovedWhenTheProcessEndsAndEveryTestPassed) {
  const ProbeRun run = runProbe("Passes");
  ASSERT_TRUE(WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0) << run.err;
  ASSERT_FALSE(run.folder.empty()) << "the probe printed no folder";
  EXPECT_FALSE(fs::exists(run.folder));
  EXPECT_FALSE(fs::exists(run.folder.parent_path()));
}

TEST(ScratchDir, IsKeptAndNamedWhenATestFailed) {
  const ProbeRun run = runProbe("Fails");
  ASSERT_TRUE(WIFEXITED(run.status) && WEXITSTATUS(run.status) != 0) << run.err;
  ASSERT_FALSE(run.folder.empty()) << "the probe printed no folder";
  EXPECT_TRUE(fs::exists(run.folder / "output.txt"));
  EXPECT_NE(run.err.find("kept the scratch folder of the failed tests: " + run.folder.parent_path().string()),
            std::string::npos)
      << run.err;
  fs::remove_all(run.folder.parent_path());
}

// A forked child that ends with exit() runs the static destructors too: it must leave its parent's folder alone.
TEST(ScratchDir, AForkedChildThatEndsNormallyLeavesItsParentsFolder) {
  const fs::path dir = scratchDirForThisTest("amos_scratch_");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) std::exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_TRUE(fs::is_directory(dir));
}

}  // namespace
}  // namespace amos::testing
