#pragma once
// A scratch folder for one test, unique to this process: several test processes (two checkouts' ctest runs, a
// test binary started by hand during ctest) may run on one machine at once, and a folder named by the test alone
// would be removed or written by another of them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace amos::testing {

// <temp>/<name>_<pid>, emptied (created, with nothing in it).
inline std::filesystem::path scratchDir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / (name + "_" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// scratchDir(prefix + the name of the test that is running).
inline std::filesystem::path scratchDirForThisTest(const std::string& prefix) {
  return scratchDir(prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

}  // namespace amos::testing
