#pragma once
// Scratch folders for tests, all inside one folder of this process (<temp>/amos_tests_<pid>): several test
// processes (two checkouts' ctest runs, a test binary started by hand during ctest) may run on one machine at once,
// and a folder named by the test alone would be removed or written by another of them.
//
// That folder is removed when the process ends normally and every test passed: a test run leaves nothing behind
// (ctest starts a process per test, and the runs of the program's tests write hundreds of MiB each, which filled a
// CI machine's disk when they were kept). A failed run keeps it, and says where, so that its outputs can be read.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

namespace amos::testing {

class ScratchRoot {
 public:
  static const std::filesystem::path& path() {
    static const ScratchRoot root;
    return root.path_;
  }

  ScratchRoot(const ScratchRoot&) = delete;
  ScratchRoot& operator=(const ScratchRoot&) = delete;

 private:
  // GoogleTest's UnitTest is made first, so that it is still there when this is destroyed (in the reverse order).
  ScratchRoot()
      : owner_((::testing::UnitTest::GetInstance(), ::getpid())),
        path_(std::filesystem::temp_directory_path() / ("amos_tests_" + std::to_string(static_cast<long>(owner_)))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }

  // A forked child that ends normally must not remove its parent's folder: only the process that made it does.
  ~ScratchRoot() {
    if (::getpid() != owner_) return;
    if (!::testing::UnitTest::GetInstance()->Passed()) {
      std::cerr << "kept the scratch folder of the failed tests: " << path_.string() << '\n';
      return;
    }
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }

  const pid_t owner_;
  const std::filesystem::path path_;
};

// <this process's scratch root>/<name>, emptied (created, with nothing in it).
inline std::filesystem::path scratchDir(const std::string& name) {
  const std::filesystem::path dir = ScratchRoot::path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// scratchDir(prefix + the name of the test that is running).
inline std::filesystem::path scratchDirForThisTest(const std::string& prefix) {
  return scratchDir(prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

}  // namespace amos::testing
