#pragma once
// For tests only: where the real test data (TUM and Bonn slices, reference trajectories, person photographs) and
// the segmentation models live, outside the repository: ../shared beside the checkout (the build's
// AMOS_SHARED_DIR), or the folder the environment variable AMOS_SHARED_DIR names at run time.
//
// A test that needs a part of it starts with AMOS_REQUIRE_SHARED("data/tum_fr2_desk_first50"): when that path is
// absent (a clone without ../shared) the test is skipped with a message saying what is missing and how to get it,
// so CTest lists it as skipped, not failed. With AMOS_REQUIRE_SHARED_DATA=1 in the environment (CI, which has the
// data) a missing path fails the test instead, so that no real-data test is skipped unnoticed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace amos::testing {

inline std::string sharedDir() {
  const char* from_environment = std::getenv("AMOS_SHARED_DIR");
  return from_environment != nullptr && *from_environment != '\0' ? from_environment : AMOS_SHARED_DIR;
}

// <shared>/<relative>, e.g. sharedPath("data/bonn_crowd_dev").
inline std::string sharedPath(const std::string& relative) {
  return (std::filesystem::path(sharedDir()) / relative).string();
}

// Why a test that needs <shared>/<relative> cannot run, or nullopt when the path is there.
inline std::optional<std::string> missingShared(const std::string& relative) {
  const std::string path = sharedPath(relative);
  if (std::filesystem::exists(path)) return std::nullopt;
  return "needs ../shared/" + relative + ": " + path +
         " is absent (put the shared test data beside the checkout as ../shared, or point the AMOS_SHARED_DIR "
         "environment variable at it)";
}

inline bool sharedDataRequired() {
  const char* flag = std::getenv("AMOS_REQUIRE_SHARED_DATA");
  return flag != nullptr && std::string(flag) == "1";
}

}  // namespace amos::testing

// Skips the current test (or fails it under AMOS_REQUIRE_SHARED_DATA=1) when <shared>/<relative> is absent. Use
// in a test body or a fixture's SetUp().
#define AMOS_REQUIRE_SHARED(relative)                                                                 \
  do {                                                                                                \
    if (const auto amos_missing_shared_ = ::amos::testing::missingShared(relative)) {                 \
      if (::amos::testing::sharedDataRequired()) FAIL() << *amos_missing_shared_;                     \
      GTEST_SKIP() << *amos_missing_shared_;                                                          \
    }                                                                                                 \
  } while (false)
